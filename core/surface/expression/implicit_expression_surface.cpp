#include "core/surface/expression/implicit_expression_surface.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "core/mesh/base_meshes.h"
#include "core/surface/box_base_mesh.h"
#include "core/surface/expression/formula_checks.h"
#include "core/surface/finite_differences.h"
#include "core/surface/projection.h"
#include "core/topology/contour_base_mesh.h"

namespace dynamesh {

namespace {

// Grid points per axis of the scans: fine when built (once), coarser at each set_time() so
// that the check costs well under a millisecond (17^3 evaluations).
constexpr int kBuildScan = 33;
constexpr int kStepScan = 17;

}  // namespace

ImplicitExpressionSurface::ImplicitExpressionSurface(const std::string& formula, const Box3& bounds,
                                                     const std::string& base_mesh_path)
    : formula_(formula),
      f_({formula}, {"x", "y", "z", "t"}, "implicit formula"),
      tape_(f_.tape_with("t", 0.0)),
      bounds_(bounds),
      base_mesh_path_(base_mesh_path) {
  for (int a = 0; a < 3; ++a)
    if (!(bounds_.min[a] < bounds_.max[a]) || !std::isfinite(bounds_.size()[a]))
      throw std::invalid_argument(
          "--bounds is empty or not finite: each minimum must be below its maximum");
  interior_ = scan_implicit(f_, formula_, bounds_, 0.0, kBuildScan).interior;
  if (!base_mesh_path_.empty()) file_mesh_ = read_triangle_mesh(base_mesh_path_);
  base_at_zero_ = build_base_mesh();
}

void ImplicitExpressionSurface::set_time(double t) {
  // Check first: a throw leaves the surface (and the adapter's mesh) at the last good time.
  const ImplicitScan scan = scan_implicit(f_, formula_, bounds_, t, kStepScan, &interior_);
  interior_ = scan.interior;
  Surface::set_time(t);
  tape_ = f_.tape_with("t", t);
}

double ImplicitExpressionSurface::value(const Vec3& p) const {
  const double x[4] = {p.x(), p.y(), p.z(), time()};
  if (tape_) {
    ForwardJet<0, 0> f[FormulaTape::kLocalStack];
    tape_->evaluate<0, 0>(x, f);
    return f[0].value;
  }
  return f_.value(x);
}

double ImplicitExpressionSurface::value_gradient(const Vec3& p, Vec3& gradient) const {
  const double t = time();
  if (tape_) {
    const double x[4] = {p.x(), p.y(), p.z(), t};
    ForwardJet<3, 1> f[FormulaTape::kLocalStack];
    tape_->evaluate<3, 1>(x, f);
    // One component at a time: a two-wide load of components the tape stored one by one
    // would wait for those stores to complete (a store-forwarding stall, ~10% of the call).
    gradient.x() = f[0].grad[0];
    gradient.y() = f[0].grad[1];
    gradient.z() = f[0].grad[2];
    return f[0].value;
  }
  return gradient_differences(
      [&](const Vec3& q) {
        const double x[4] = {q.x(), q.y(), q.z(), t};
        return f_.value(x);
      },
      p, difference_step(), gradient);
}

Mat3 ImplicitExpressionSurface::hessian(const Vec3& p) const {
  const double t = time();
  if (tape_) {
    const double x[4] = {p.x(), p.y(), p.z(), t};
    ForwardJet<3, 2> f[FormulaTape::kLocalStack];
    tape_->evaluate<3, 2>(x, f);
    Mat3 hessian;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) hessian(i, j) = f[0].hessian(i, j);
    return hessian;
  }
  return hessian_differences(
      [&](const Vec3& q) {
        const double x[4] = {q.x(), q.y(), q.z(), t};
        return f_.value(x);
      },
      p, kSecondDifferenceStep * length_scale());
}

Mesh48 ImplicitExpressionSurface::base_mesh() const {
  if (base_at_zero_ && time() == 0.0) return *base_at_zero_;
  return build_base_mesh();
}

Mesh48 ImplicitExpressionSurface::build_base_mesh() const {
  if (file_mesh_) {
    Mesh48 mesh = file_base_mesh();
    check_orientation(mesh, "base mesh " + base_mesh_path_);
    return mesh;
  }
  // A star-shaped surface gets the box of quads (few, well-shaped base quads); any other
  // (a torus, two blobs, a dumbbell bent round) is contoured from F itself (issue 16).
  if (is_star_shaped()) {
    Mesh48 mesh = box_base_mesh();
    check_orientation(mesh, "the box base mesh");
    return mesh;
  }
  Mesh48 mesh = make_contour_base_mesh(*this);
  check_orientation(mesh, "the contoured base mesh");
  return mesh;
}

Mesh48 ImplicitExpressionSurface::box_base_mesh() const {
  // Quads of about equal size on the box's sides: 2 along its shortest axis.
  const Vec3 size = bounds_.size();
  std::array<int, 3> counts;
  for (int a = 0; a < 3; ++a)
    counts[a] = std::clamp(static_cast<int>(std::lround(2.0 * size[a] / size.minCoeff())), 2, 8);
  // Each box vertex goes to where the ray from the interior point towards it first leaves the
  // inside (bracketed on a fine march, then bisected); Newton polishes the rest.
  const Vec3 c = interior_;
  const double t = time();
  auto F = [&](const Vec3& p) {
    const double x[4] = {p.x(), p.y(), p.z(), t};
    return f_.value(x);
  };
  auto place = [&](const Vec3& q) {
    constexpr int kMarch = 128;
    double lo = 0.0;
    for (int i = 1; i <= kMarch; ++i) {
      const double s = static_cast<double>(i) / kMarch;
      if (F(c + s * (q - c)) < 0) {
        lo = s;
        continue;
      }
      double hi = s;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (F(c + mid * (q - c)) < 0 ? lo : hi) = mid;
      }
      return Vec3(c + hi * (q - c));
    }
    throw std::invalid_argument(
        "implicit formula '" + formula_ + "': the ray from the inside point " + format_point(c) +
        " towards " + format_point(q) + " never leaves the inside; enlarge --bounds");
  };
  try {
    return make_projected_box_mesh(*this, bounds_, counts, place);
  } catch (const std::logic_error& e) {
    if (dynamic_cast<const std::invalid_argument*>(&e)) throw;
    throw std::invalid_argument(
        "implicit formula '" + formula_ +
        "': a base mesh vertex did not converge onto the surface (is the gradient zero on "
        "it, e.g. F squared?); try another formula for the same surface or --base-mesh FILE");
  }
}

bool ImplicitExpressionSurface::is_star_shaped() const {
  // Placing the box by rays from the interior point is right only when every ray leaves the
  // inside once and for all (the surface is star-shaped around it, so of sphere topology).
  // Checked along kDirections rays spread evenly over the sphere (a Fibonacci lattice), each
  // marched to the box in kMarch steps: a torus or a dumbbell bent around fails here and is
  // contoured instead of getting a base mesh that wraps the wrong shape.
  constexpr int kDirections = 400, kMarch = 128;
  const Vec3 c = interior_;
  const double t = time();
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kDirections, r = std::sqrt(1.0 - z * z);
    const Vec3 d(r * std::cos(golden * i), r * std::sin(golden * i), z);
    double exit = HUGE_VAL;
    for (int a = 0; a < 3; ++a) {
      if (d[a] > 0) exit = std::min(exit, (bounds_.max[a] - c[a]) / d[a]);
      if (d[a] < 0) exit = std::min(exit, (bounds_.min[a] - c[a]) / d[a]);
    }
    bool left = false;
    for (int k = 1; k <= kMarch; ++k) {
      const Vec3 p = c + (exit * k / kMarch) * d;
      const double x[4] = {p.x(), p.y(), p.z(), t};
      const bool inside = f_.value(x) < 0;
      if (!inside) left = true;
      if (inside && left) return false;
    }
  }
  return true;
}

namespace {

// The surface F = 0 inside bounded --bounds is closed, so its base mesh must be closed too:
// every edge shared by exactly two triangles. An open one would be adapted as a patch.
void check_closed(const std::string& path, const std::vector<std::array<std::uint32_t, 3>>& tris) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t open = 0;
  std::pair<std::uint32_t, std::uint32_t> example;
  for (const auto& [edge, n] : uses)
    if (n != 2) {
      if (open++ == 0) example = edge;
    }
  if (open > 0)
    throw std::invalid_argument(
        "base mesh " + path + ": " + std::to_string(open) +
        " edges are not shared by exactly two triangles (e.g. vertices " +
        std::to_string(example.first) + " and " + std::to_string(example.second) +
        "): an implicit surface is closed, so its base mesh must be a closed manifold too");
}

}  // namespace

Mesh48 ImplicitExpressionSurface::file_base_mesh() const {
  std::vector<Vec3> positions = file_mesh_->positions;
  std::vector<std::array<std::uint32_t, 3>> triangles = file_mesh_->triangles;
  check_closed(base_mesh_path_, triangles);
  // OBJ and PLY writers disagree on winding: face the majority outwards (F grows outwards),
  // then let check_orientation() catch a mesh that is inconsistent.
  double outward = 0.0;
  for (const auto& tri : triangles) {
    const Vec3 &a = positions[tri[0]], &b = positions[tri[1]], &c = positions[tri[2]];
    Vec3 g;
    value_gradient((a + b + c) / 3.0, g);
    outward += (b - a).cross(c - a).dot(g.normalized());
  }
  if (outward < 0)
    for (auto& tri : triangles) std::swap(tri[1], tri[2]);
  Mesh48 mesh;
  try {
    mesh = make_48_mesh(positions, {}, triangles);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("base mesh " + base_mesh_path_ + ": " + e.what() +
                                "; it must be a manifold, consistently oriented triangle mesh");
  }
  for (const Vertex v : mesh.live_vertices()) {
    const ProjectionResult r = project_to_surface(*this, mesh.position(v));
    if (!r.converged)
      throw std::invalid_argument("base mesh " + base_mesh_path_ + ": the vertex at " +
                                  format_point(mesh.position(v)) +
                                  " does not converge onto the surface; the base mesh must lie "
                                  "close to F = 0");
    mesh.position(v) = r.point;
  }
  return mesh;
}

void ImplicitExpressionSurface::check_orientation(const Mesh48& mesh,
                                                  const std::string& source) const {
  // After projection every face must still face outwards: a face turned over means the base
  // mesh folded onto the surface (not star-shaped for the box, too coarse or misplaced for a
  // file), and adapting it would only refine the fold.
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    const Vec3 &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    Vec3 g;
    value_gradient((a + b + c) / 3.0, g);
    if (!((b - a).cross(c - a).dot(g) > 0))
      throw std::invalid_argument(
          source + " folds over when placed on the surface of '" + formula_ + "' near " +
          format_point(Vec3((a + b + c) / 3.0)) +
          (file_mesh_ ? "; give a finer base mesh closer to the surface"
                      : "; give --base-mesh FILE, or tighter --bounds (the contour's grid spacing "
                        "is a 24th of their longest side)"));
  }
}

}  // namespace dynamesh
