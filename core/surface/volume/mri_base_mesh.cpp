#include "core/surface/volume/mri_base_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/surface/volume/cuberille_base_mesh.h"
#include "core/topology/contour_base_mesh.h"
#include "core/topology/topology_events.h"

namespace dynamesh {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// A base mesh as plain arrays: positions by vertex slot, triangles newest vertex first (the
// order from_base_triangles takes back).
struct PlainMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

PlainMesh plain(const Mesh48& mesh) {
  PlainMesh out;
  std::vector<std::uint32_t> id(mesh.vertex_capacity(), kInvalidIndex);
  for (const Vertex v : mesh.live_vertices()) {
    id[v.idx] = static_cast<std::uint32_t>(out.positions.size());
    out.positions.push_back(mesh.position(v));
  }
  for (const Face f : mesh.live_faces()) {
    const auto c = mesh.vertices(f);
    out.triangles.push_back({id[c[0].idx], id[c[1].idx], id[c[2].idx]});
  }
  return out;
}

}  // namespace

Mesh48 make_mri_base_mesh(const ImplicitSurface& surface, const MriBaseMeshOptions& options,
                          MriBaseMeshInfo* info) {
  MriBaseMeshInfo local;
  CuberilleOptions cuberille_options;
  cuberille_options.cell_size = options.cell_size;
  Mesh48 cuberille = make_cuberille_base_mesh(surface, surface.bounds(), cuberille_options);
  PlainMesh contour;
  try {
    ContourBaseOptions contour_options;
    contour_options.spacing = options.cell_size;
    contour = plain(make_contour_base_mesh(surface, contour_options));
  } catch (const std::invalid_argument&) {
    if (info) *info = local;
    return cuberille;  // no crossing on the contour's grid: the cuberille is all there is
  }
  std::size_t pieces = 0;
  const std::vector<std::uint32_t> piece =
      vertex_pieces(contour.triangles, contour.positions.size(), pieces);
  local.contour_pieces = pieces;
  // Each cuberille vertex votes for the piece of its nearest contour vertex; both lie on
  // F = 0, so the pieces the cuberille follows get its votes. Brute force: a few thousand
  // vertices each, once per run.
  const PlainMesh base = plain(cuberille);
  std::vector<std::size_t> votes(pieces, 0);
  for (const Vec3& p : base.positions) {
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t nearest = 0;
    for (std::uint32_t v = 0; v < contour.positions.size(); ++v) {
      const double d = (contour.positions[v] - p).squaredNorm();
      if (d < best) best = d, nearest = v;
    }
    ++votes[piece[nearest]];
  }
  std::size_t own = 0;
  for (std::size_t k = 1; k < pieces; ++k)
    if (votes[k] > votes[own]) own = k;
  // How much of its own piece the cuberille follows: a contour vertex of that piece with a
  // cuberille vertex within one cell.
  std::size_t in_own = 0, covered = 0;
  const double reach2 = options.cell_size * options.cell_size;
  for (std::uint32_t v = 0; v < contour.positions.size(); ++v) {
    if (piece[v] != own) continue;
    ++in_own;
    for (const Vec3& p : base.positions)
      if ((contour.positions[v] - p).squaredNorm() <= reach2) {
        ++covered;
        break;
      }
  }
  for (std::size_t k = 0; k < pieces; ++k)
    if (k != own) local.votes_elsewhere += votes[k];
  local.coverage = in_own ? double(covered) / double(in_own) : 0.0;
  if (local.coverage < options.min_coverage) {
    local.contour_whole = true;
    if (info) *info = local;
    return Mesh48::from_base_triangles(std::move(contour.positions), {}, contour.triangles);
  }
  // The cuberille and the contour's other pieces, renumbered into one vertex list.
  PlainMesh merged = base;
  std::vector<std::uint32_t> id(contour.positions.size(), kInvalidIndex);
  for (const Triangle& t : contour.triangles) {
    // A piece that some cuberille vertex is nearest to is (at least partly) the cuberille's
    // too: a lobe that its cells join to the largest piece. Added, it would lie on the
    // cuberille's sheet (Colin27 closing 2, 10 mm deep: 38 self-intersecting pairs).
    if (votes[piece[t[0]]] > 0) continue;
    Triangle out;
    for (int c = 0; c < 3; ++c) {
      std::uint32_t& slot = id[t[c]];
      if (slot == kInvalidIndex) {
        slot = static_cast<std::uint32_t>(merged.positions.size());
        merged.positions.push_back(contour.positions[t[c]]);
      }
      out[c] = slot;
    }
    merged.triangles.push_back(out);
  }
  for (std::size_t k = 0; k < pieces; ++k) local.pieces_added += votes[k] == 0;
  if (info) *info = local;
  if (local.pieces_added == 0) return cuberille;
  return Mesh48::from_base_triangles(std::move(merged.positions), {}, merged.triangles);
}

double mri_start_depth(const std::vector<CriticalPoint>& points, double depth,
                       const MriBaseMeshOptions& options) {
  const double reach = 0.5 * options.cell_size;
  // Candidates: `depth` itself, then the depths just clear of each point, shallower first
  // (each point's depth less `reach`); the deepest clear one wins.
  std::vector<double> candidates{depth};
  for (const CriticalPoint& p : points) candidates.push_back(-p.value - reach);
  std::sort(candidates.begin(), candidates.end(), std::greater<>());
  for (const double d : candidates) {
    if (d > depth || d <= 0.0) continue;
    const bool clear = std::none_of(points.begin(), points.end(), [&](const CriticalPoint& p) {
      return std::abs(d + p.value) < reach;
    });
    if (clear) return d;
  }
  return 0.0;
}

}  // namespace dynamesh
