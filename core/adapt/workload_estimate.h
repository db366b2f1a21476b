// How much work a surface asks for at a threshold T, estimated before any mesh is built
// (issue 15: a formula whose surface needs more than the budgets is refused up front with the
// estimate, rather than refined for minutes until a budget stops it).
//
// An adapted triangle of edge l on a surface of curvature k has geometric error about
// k l^2 / 4 (the sag of a right isosceles triangle's circumcircle, circumradius l / sqrt 2),
// so where the error is held near T a triangle covers about 2 T / k of area: the mesh needs
// about integral(k dA) / (2 T) triangles, k the larger principal curvature. Samples are
// density * area. Both integrals are measured on a grid: over the parameter domain for a
// parametric surface (|Su x Sv| du dv), and at the crossings of grid lines with F = 0 for an
// implicit one (each crossing of an axis-a line stands for h^2 / |n_a| of area, so summing
// h^2 / (|n_x| + |n_y| + |n_z|) over all crossings estimates the area, Crofton-style).
//
// The grid also finds what no mesh can follow: a value, gradient or curvature that is not
// finite on the surface, and (implicit) a sign change of F that is a jump rather than a zero
// (bisected to 1e-12 of the cell, F still differs by a finite amount: a step, not a
// surface). A grid misses detail finer than its cells, so the estimate is a lower bound:
// a refusal is certain, a pass is not a promise (the budgets still stop the rest).
#pragma once

#include <string>

#include "core/surface/surface.h"

namespace dynamesh {

struct WorkloadEstimate {
  double area = 0.0;       // of the surface, scene units squared
  double curvature = 0.0;  // integral of max(|k1|, |k2|) dA
  double triangles = 0.0;  // integral(k dA) / (2 T), at least the base mesh's
  double samples = 0.0;    // density * area
  std::string problem;     // non-empty: what makes the surface impossible to mesh, and where
};

// `resolution`: grid points per axis. Evaluates the surface at its current time. For a
// parametric surface the triangle count is also counted by refining squares of the domain
// until S is within T of their bilinear interpolation (up to max_triangles, so the cost stays
// bounded; the count is then "more than max_triangles").
WorkloadEstimate estimate_workload(const Surface& surface, double threshold, double density,
                                   double max_triangles, int resolution = 48);

}  // namespace dynamesh
