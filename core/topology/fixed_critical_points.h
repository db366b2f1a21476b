// Fixed critical points (issue 16, event detection for mri): when F(p, t) = G(p) + c(t), as for
// the layers of a distance field (mri: G the signed distance, c the depth), grad F does not
// depend on t, so F's critical points are G's, the same at every time, and F = 0 passes one
// exactly when c(t) crosses -G there. They are found once per field, on its voxel grid: a cell
// whose eight nodes' central-difference gradients change sign in all three components may hold
// one; Newton's method on the smooth field's gradient (exact Hessian) refines it, as
// find_critical_points does on the analytic scenes. Sorted by G, the monitor then finds a
// step's events by a binary search on c (topology_events.h).
//
// A distance field smoothed over a voxel staircase has many shallow critical points: pairs of
// adjacent index (a minimum and a saddle, two saddles) a fraction of a millimetre apart in
// value, each pair a lobe or a handle that exists over that fraction of the depth only. Such a
// pair is cancelled when its persistence (the difference of its two values) is below
// `min_persistence`, the mesh's error bound T: cancelling a pair of persistence p changes F by
// at most p / 2 (Edelsbrunner, Morozov & Pascucci, "Persistence-sensitive simplification of
// functions on 2-manifolds", SoCG 2006; the same bound holds for the cancellation of one pair in
// 3-D), and with |grad F| close to 1 the layer by about as much, less than a mesh that is
// allowed an error of T can show. Pairs are formed greedily, smallest persistence first, among
// points closer than `pair_radius` (a stand-in for the pairing along F's gradient lines that a
// full persistence computation would give; the tests check the events that remain against an
// independent flood fill of the layers).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/surface/volume/bspline_field.h"
#include "core/surface/volume/progress.h"
#include "core/topology/critical_points.h"

namespace dynamesh {

struct FixedCriticalPointsOptions {
  // Only critical points with G in [min_value, max_value] are kept (those of partners of
  // cancelled pairs may lie up to min_persistence outside).
  double min_value = -HUGE_VAL;
  double max_value = HUGE_VAL;
  double min_persistence = 0.0;  // pairs of adjacent index closer in G than this cancel
  double pair_radius = 0.0;      // world units; 0: three voxel diagonals
  ProgressCallback progress;     // stage "critical points", 0..1 (the voxel search)
};

struct FixedCriticalPoints {
  std::vector<CriticalPoint> points;  // value = G there; sorted by value
  std::size_t candidates = 0;         // found by Newton in the band, before cancelling
  std::size_t cancelled = 0;          // points removed in pairs
  double spacing = 0.0;               // the field's largest voxel side
  double seconds = 0.0;               // what the search (and the cancelling) cost
};

// Every critical point in the band (min_persistence widens it; nothing cancelled yet): the
// voxel search, done once per field.
FixedCriticalPoints find_fixed_critical_points(const CubicBSplineField& field,
                                               const FixedCriticalPointsOptions& options);
// The points of `all` left once pairs of persistence below `min_persistence` within
// `pair_radius` (0: three voxel diagonals of `all`) are cancelled, restricted to G in
// [min_value, max_value]: cheap, done per resolution.
FixedCriticalPoints cancel_shallow_pairs(const FixedCriticalPoints& all,
                                         const FixedCriticalPointsOptions& options);

// Implemented by surfaces F(p, t) = G(p) + c(t) (mri), next to ImplicitSurface: the topology
// monitor asks for G's critical points once and reads each step's events off them.
class FixedCriticalField {
 public:
  virtual ~FixedCriticalField() = default;
  // G's critical points over the surface's whole animation, pairs of persistence below
  // `resolution` cancelled; computed on the first call for a resolution, then kept.
  virtual const FixedCriticalPoints& fixed_critical_points(double resolution) const = 0;
  // c(t) at the surface's current time.
  virtual double time_offset() const = 0;
};

}  // namespace dynamesh
