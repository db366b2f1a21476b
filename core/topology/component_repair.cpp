#include "core/topology/component_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/topology/critical_points.h"
#include "core/topology/marching_tetrahedra.h"
#include "core/topology/topology_events.h"
#include "core/topology/triangle_pairing.h"

namespace dynamesh {

namespace {

using Triangle = std::array<std::uint32_t, 3>;
constexpr double kMargin = 0.05;  // a contour vertex's distance from its edge's ends (fraction)

LocalRepairResult refused(const std::string& why) {
  LocalRepairResult r;
  r.why_not = why;
  return r;
}

// The critical point next to `start` at the surface's current time: the event's position is
// interpolated between two steps' critical points, while the contour needs a grid node where F
// has the new component's sign.
Vec3 current_critical_point(const ImplicitSurface& surface, const Vec3& start, double reach) {
  const FieldJet jet = [&surface](const Vec3& p, Vec3& g, Mat3& h) {
    return surface.value_gradient_hessian(p, g, h);
  };
  Box3 region;
  region.extend(start - Vec3::Constant(reach));
  region.extend(start + Vec3::Constant(reach));
  CriticalPoint cp;
  return refine_critical_point(jet, start, region, 1e-10 * reach, cp) ? cp.position : start;
}

// A grid of 2n cells of side h along each axis with its middle node at `centre`.
ContourGrid centred_grid(const Vec3& centre, double h, int n) {
  ContourGrid grid;
  grid.box.extend(centre - Vec3::Constant(n * h));
  grid.box.extend(centre + Vec3::Constant(n * h));
  grid.cells = {2 * n, 2 * n, 2 * n};
  return grid;
}

// The nodes of the region where `values` < 0 that holds `start`, joined along the edges of
// marching tetrahedra's Kuhn triangulation (offsets of 0s and 1s of one sign: 14 neighbours),
// the only pairs of nodes its contour does not separate. False when the region reaches a side
// of the grid (the component is not enclosed by it).
bool flood_region(const ContourGrid& grid, const std::vector<double>& values, int start_i,
                  std::vector<char>& in) {
  const int nx = grid.cells[0] + 1, ny = grid.cells[1] + 1, nz = grid.cells[2] + 1;
  const auto id = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * ny + j) * nx + i;
  };
  in.assign(values.size(), 0);
  std::vector<std::array<int, 3>> stack{{start_i, start_i, start_i}};
  in[id(start_i, start_i, start_i)] = 1;
  while (!stack.empty()) {
    const auto [i, j, k] = stack.back();
    stack.pop_back();
    if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) return false;
    for (int bits = 1; bits < 8; ++bits)
      for (const int sign : {-1, 1}) {
        const int a = i + sign * (bits & 1), b = j + sign * (bits >> 1 & 1),
                  c = k + sign * (bits >> 2 & 1);
        const std::size_t n = id(a, b, c);
        if (in[n] || values[n] >= 0.0) continue;
        in[n] = 1;
        stack.push_back({a, b, c});
      }
  }
  return true;
}

}  // namespace

LocalRepairResult add_born_component(Mesh48& mesh, const ImplicitSurface& surface,
                                     const Vec3& event, const LocalRepairOptions& options) {
  const double h = options.spacing, reach = 4.0 * options.radius;
  if (!(h > 0.0) || !(reach > h)) return refused("birth: no contour spacing");
  const Vec3 centre = current_critical_point(surface, event, options.radius);
  // A bubble of outside (F > 0 at a maximum) is contoured as the inside of -F, then turned to
  // face along grad F, into the bubble.
  const double sign = surface.value(centre) < 0.0 ? 1.0 : -1.0;
  ContourGrid grid;
  std::vector<double> values;
  std::vector<char> in;
  bool enclosed = false;
  for (int n = 3; !enclosed && n * h <= reach; n *= 2) {
    grid = centred_grid(centre, h, n);
    values = sample_grid(surface, grid);
    for (double& v : values) v *= sign;
    if (values[values.size() / 2] >= 0.0)
      return refused("birth: F at the critical point has not crossed zero yet");
    enclosed = flood_region(grid, values, n, in);
  }
  if (!enclosed) return refused("birth: the new component reaches past the repair's reach");
  // Only this component is contoured: F's own sign elsewhere in the box (another part of the
  // surface) is not asked about. No node outside the region is a Kuhn neighbour of one in it,
  // so the region's contour is exactly as on the whole grid.
  Box3 extent;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!in[i]) values[i] = std::max(values[i], 1.0);
  }
  ContourMesh contour = marching_tetrahedra(grid, values, kMargin);
  for (const Vec3& p : contour.positions) extent.extend(p);
  extent = extent.grown(h);
  for (const Vertex v : mesh.live_vertices()) {
    if (extent.contains(mesh.position(v)))
      return refused("birth: the mesh already has a vertex where the new component is");
  }
  const MeshTopologySummary shape = summarize_topology(contour.triangles, contour.positions.size());
  if (shape.components != 1 || shape.euler != 2)
    return refused("birth: the new component's contour is not one sphere");
  std::vector<Vec3> positions(contour.positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    std::array<Vec3, 2> edge = contour.edges[i];  // (inside, outside) of sign * F
    if (sign < 0.0) std::swap(edge[0], edge[1]);
    positions[i] = root_on_edge(surface, edge, kMargin);
  }
  if (sign < 0.0)
    for (Triangle& t : contour.triangles) std::swap(t[1], t[2]);
  const std::vector<std::int64_t> partner = pair_triangles(positions, contour.triangles);
  if (std::find(partner.begin(), partner.end(), -1) != partner.end())
    return refused("birth: the new component's triangles do not pair");
  LocalRepairResult r;
  r.new_vertices =
      mesh.replace_region({}, {}, positions, refinement_edge_first(contour.triangles, partner));
  r.repaired = true;
  r.added_faces = contour.triangles.size();
  r.spacing = h;
  return r;
}

LocalRepairResult remove_dead_component(Mesh48& mesh, const ImplicitSurface& surface,
                                        const Vec3& centre, const LocalRepairOptions& options) {
  if (!(options.spacing > 0.0)) return refused("death: no contour spacing");
  std::size_t count = 0;
  const std::vector<std::uint32_t> piece = vertex_pieces(mesh, count);
  Vertex nearest;
  double best = HUGE_VAL;
  for (const Vertex v : mesh.live_vertices()) {
    const double d = (mesh.position(v) - centre).norm();
    if (d < best) best = d, nearest = v;
  }
  if (!nearest.is_valid()) return refused("death: the mesh is empty");
  Box3 extent;
  for (const Vertex v : mesh.live_vertices()) {
    if (piece[v.idx] != piece[nearest.idx]) continue;
    if ((mesh.position(v) - centre).norm() > options.radius)
      return refused("death: the component nearest the event reaches past the repair's radius");
    extent.extend(mesh.position(v));
  }
  // Gone means F has one sign over the component's box (grown by a quarter and by half the
  // repair's spacing), sampled at half that spacing: no zero set left there to mesh.
  const Vec3 grow = 0.25 * extent.size() + Vec3::Constant(0.5 * options.spacing);
  ContourGrid grid;
  grid.box.extend(extent.min - grow);
  grid.box.extend(extent.max + grow);
  grid = make_contour_grid(grid.box, 0.5 * options.spacing);
  const std::vector<double> values = sample_grid(surface, grid);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  if (*lo < 0.0 && *hi > 0.0)
    return refused("death: F still crosses zero where the dying component is");
  std::vector<Face> removed;
  for (const Face f : mesh.live_faces())
    if (piece[mesh.vertex(f, 0).idx] == piece[nearest.idx]) removed.push_back(f);
  mesh.replace_region(removed, {}, {}, {});
  LocalRepairResult r;
  r.repaired = true;
  r.removed_faces = removed.size();
  r.spacing = options.spacing;
  return r;
}

}  // namespace dynamesh
