#include "core/topology/topology_events.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace dynamesh {

namespace {

// Union-find over vertex ids.
struct Components {
  explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
  std::vector<std::uint32_t> parent;
};

// Morse theory: passing a critical point of index i with F decreasing through 0 attaches an
// i-handle to the inside {F < 0}; increasing, removes one.
TopologyEventKind kind_of(int index, bool going_negative) {
  switch (index) {
    case 0:
      return going_negative ? TopologyEventKind::kBirth : TopologyEventKind::kDeath;
    case 1:
      return going_negative ? TopologyEventKind::kMerge : TopologyEventKind::kSplit;
    case 2:
      return going_negative ? TopologyEventKind::kHoleCloses : TopologyEventKind::kHoleOpens;
    default:  // a maximum: a bubble of outside inside the solid vanishes or appears
      return going_negative ? TopologyEventKind::kDeath : TopologyEventKind::kBirth;
  }
}

// Attaching an i-handle to the inside {F < 0} changes its Euler characteristic by (-1)^i, and
// the boundary surface's by twice that; removing one, by minus that.
long euler_change(int index, bool going_negative) {
  const long handle = index % 2 == 0 ? 2 : -2;
  return going_negative ? handle : -handle;
}

// Whether the piecewise-linear contour of a grid of cell diagonal `diagonal` may disagree with
// F's true topology near `cp`: F deviates from its linear interpolant over a cell by up to
// about |Hess F| diagonal^2 / 8 per edge, and the whole neighbourhood of the critical point
// within a cell by |Hess F| diagonal^2 / 2 (its second-order model).
bool within_resolution(const CriticalPoint& cp, double diagonal) {
  return std::abs(cp.value) <= 0.5 * cp.curvature * diagonal * diagonal;
}

// Whether a critical point lies inside, F < 0. One whose value is zero to within rounding
// (1e-9 of the grid's resolution bound: an event on a step time, such as the torus pinched at
// t = 0.09 / 0.12 = 0.75) counts as outside, as F = 0 does: at that instant the surface is a
// double cone, and only the side where the cone's two sheets are apart (two tips, or two
// blobs touching) has an embedded mesh; the sign of F's rounding error must not choose.
bool inside(const CriticalPoint& cp, double diagonal) {
  return cp.value < -1e-9 * 0.5 * cp.curvature * diagonal * diagonal;
}

}  // namespace

const char* to_string(TopologyEventKind kind) {  // declared in topology_event.h
  switch (kind) {
    case TopologyEventKind::kBirth:
      return "birth";
    case TopologyEventKind::kDeath:
      return "death";
    case TopologyEventKind::kMerge:
      return "merge";
    case TopologyEventKind::kSplit:
      return "split";
    case TopologyEventKind::kHoleCloses:
      return "hole-closes";
    case TopologyEventKind::kHoleOpens:
      return "hole-opens";
    case TopologyEventKind::kMismatch:
      return "mismatch";
  }
  return "?";
}

MeshTopologySummary summarize_topology(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                       std::size_t vertex_count) {
  Components c(vertex_count);
  std::vector<char> used(vertex_count, 0);
  for (const auto& t : triangles) {
    for (const std::uint32_t v : t) used[v] = 1;
    c.join(t[0], t[1]);
    c.join(t[1], t[2]);
  }
  MeshTopologySummary s;
  long vertices = 0;
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    if (!used[v]) continue;
    ++vertices;
    s.components += c.find(v) == v;
  }
  // Closed: every edge is shared by two triangles.
  const auto faces = static_cast<long>(triangles.size());
  s.euler = vertices - 3 * faces / 2 + faces;
  return s;
}

std::vector<std::uint32_t> vertex_pieces(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                         std::size_t vertex_count, std::size_t& count) {
  Components c(vertex_count);
  for (const auto& t : triangles) {
    c.join(t[1], t[0]);
    c.join(t[2], t[0]);
  }
  std::vector<std::uint32_t> piece(vertex_count), label(vertex_count, kInvalidIndex);
  count = 0;
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    std::uint32_t& l = label[c.find(v)];
    if (l == kInvalidIndex) l = static_cast<std::uint32_t>(count++);
    piece[v] = l;
  }
  return piece;
}

std::vector<std::array<std::uint32_t, 3>> live_triangles(const Mesh48& mesh) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(mesh.n_faces());
  for (const Face f : mesh.live_faces()) {
    const auto v = mesh.vertices(f);
    triangles.push_back({v[0].idx, v[1].idx, v[2].idx});
  }
  return triangles;
}

MeshTopologySummary summarize_topology(const Mesh48& mesh) {
  return summarize_topology(live_triangles(mesh), mesh.vertex_capacity());
}

std::vector<std::uint32_t> vertex_pieces(const Mesh48& mesh, std::size_t& count) {
  return vertex_pieces(live_triangles(mesh), mesh.vertex_capacity(), count);
}

TopologyMonitor::TopologyMonitor(const ContourBaseOptions& grid, double resolution)
    : grid_options_(grid), resolution_(resolution) {}

ContourGrid TopologyMonitor::grid_for(const ImplicitSurface& surface) const {
  const Box3 box = surface.bounds();
  const double spacing =
      grid_options_.spacing > 0
          ? grid_options_.spacing
          : box.size().maxCoeff() / std::max(2, grid_options_.cells_along_longest);
  return make_contour_grid(box, spacing);
}

void TopologyMonitor::reset(const ImplicitSurface& surface, const Mesh48& mesh) {
  mesh_topology_ = summarize_topology(mesh);
  previous_time_ = surface.time();
  if (const auto* field = dynamic_cast<const FixedCriticalField*>(&surface)) {
    fixed_ = &field->fixed_critical_points(resolution_);
    previous_offset_ = field->time_offset();
    // A local repair cuts two of these around an event and contours at half of one
    // (adapter_topology.cpp): two voxels, the finest detail the distance holds.
    spacing_ = 2.0 * fixed_->spacing;
    diagonal_ = std::sqrt(3.0) * fixed_->spacing;
    previous_ = fixed_->points;
    for (CriticalPoint& cp : previous_) cp.value += previous_offset_;
    return;
  }
  const ContourGrid grid = grid_for(surface);
  spacing_ = grid.spacing().maxCoeff();
  diagonal_ = grid.spacing().norm();
  previous_ = find_critical_points(surface, grid, sample_field(surface, grid), HUGE_VAL);
}

std::optional<double> TopologyMonitor::clear_level(double diagonal, double fraction,
                                                   const Box3* within) const {
  // F - L >= margin where the point is outside (as check() counts sides), F - L <= -margin
  // where it is inside.
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  for (const CriticalPoint& cp : previous_) {
    if (within && !within->contains(cp.position)) continue;
    const double margin = fraction * 0.5 * cp.curvature * diagonal * diagonal;
    if (inside(cp, diagonal_))
      lo = std::max(lo, cp.value + margin);
    else
      hi = std::min(hi, cp.value - margin);
  }
  if (lo > hi) return std::nullopt;
  return std::clamp(0.0, lo, hi);
}

TopologyCheck TopologyMonitor::check_fixed(const FixedCriticalField& field, double time) {
  TopologyCheck out;
  out.contour_trusted = false;
  out.expected_euler = mesh_topology_.euler;
  const double c0 = previous_offset_, c1 = field.time_offset();
  const double t0 = previous_time_;
  // F = G + c changes sign at a point only if -G lies between c0 and c1 (within the rounding
  // that `inside` allows for).
  const double slack = 1e-6 * (1.0 + std::abs(c0) + std::abs(c1));
  const auto& points = fixed_->points;
  const auto first =
      std::lower_bound(points.begin(), points.end(), -std::max(c0, c1) - slack,
                       [](const CriticalPoint& cp, double value) { return cp.value < value; });
  for (auto it = first; it != points.end() && it->value <= -std::min(c0, c1) + slack; ++it) {
    CriticalPoint before = *it, after = *it;
    before.value += c0;
    after.value += c1;
    const bool now_inside = inside(after, diagonal_);
    if (inside(before, diagonal_) == now_inside) continue;
    const double s = std::clamp(before.value / (before.value - after.value), 0.0, 1.0);
    out.events.push_back({t0 + s * (time - t0), it->position, kind_of(it->index, now_inside)});
    out.expected_euler += euler_change(it->index, now_inside);
  }
  // Events in the order they happen.
  std::sort(out.events.begin(), out.events.end(),
            [](const TopologyEvent& a, const TopologyEvent& b) { return a.time < b.time; });
  for (std::size_t i = 0; i < previous_.size(); ++i) previous_[i].value = points[i].value + c1;
  previous_offset_ = c1;
  previous_time_ = time;
  out.rebase = !out.events.empty();
  return out;
}

TopologyCheck TopologyMonitor::check(const ImplicitSurface& surface) {
  const auto start = std::chrono::steady_clock::now();
  if (fixed_) {
    TopologyCheck out =
        check_fixed(dynamic_cast<const FixedCriticalField&>(surface), surface.time());
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  TopologyCheck out;
  const ContourGrid grid = grid_for(surface);
  spacing_ = grid.spacing().maxCoeff();
  diagonal_ = grid.spacing().norm();
  const GridField field = sample_field(surface, grid);
  std::vector<CriticalPoint> now = find_critical_points(surface, grid, field, HUGE_VAL);
  const double t0 = previous_time_, t1 = surface.time();
  const double reach = 2.0 * grid.spacing().maxCoeff();
  const double diagonal = grid.spacing().norm();
  out.expected_euler = mesh_topology_.euler;
  for (const CriticalPoint& cp : now) {
    out.contour_trusted = out.contour_trusted && !within_resolution(cp, diagonal);
    const CriticalPoint* match = nullptr;
    for (const CriticalPoint& old : previous_) {
      if (old.index != cp.index) continue;
      const double d = (old.position - cp.position).norm();
      if (d < reach && (!match || d < (match->position - cp.position).norm())) match = &old;
    }
    if (!match) continue;
    const bool now_inside = inside(cp, diagonal);
    if (inside(*match, diagonal) == now_inside) continue;
    const double s = std::clamp(match->value / (match->value - cp.value), 0.0, 1.0);
    out.events.push_back({t0 + s * (t1 - t0), (1 - s) * match->position + s * cp.position,
                          kind_of(cp.index, now_inside)});
    out.expected_euler += euler_change(cp.index, now_inside);
  }
  previous_ = std::move(now);
  previous_time_ = t1;

  // Safety net: the contour of the same grid against the mesh.
  const ContourMesh contour = marching_tetrahedra(grid, field.values);
  out.contour = summarize_topology(contour.triangles, contour.positions.size());
  const bool mismatch = out.contour_trusted && !(out.contour == mesh_topology_);
  out.rebase = !out.events.empty() || mismatch;
  if (mismatch && out.events.empty())
    out.events.push_back({t1, grid.box.center(), TopologyEventKind::kMismatch});
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace dynamesh
