// What the re-meshing comparison (issue 17, bench/compare_openvdb.cpp) measures, for any
// triangle mesh: the dense L-infinity error against an implicit surface (the tests' own
// independent measurement, tests/unit/dense_error.h, applied to a triangle soup so that a
// mesh from another mesher is judged exactly as ours), vertex survival between two frames,
// and the CSV the plots are drawn from. No OpenVDB here: the unit tests check it.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "core/mesh/mesh48.h"
#include "core/surface/surface.h"

namespace dynamesh::compare {

struct TriangleSoup {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The live faces of a 4-8 mesh, in live_faces() order.
TriangleSoup soup_of(const Mesh48& mesh);

// Largest distance to `surface` over every triangle's `points_per_face` uniformly random
// points, its vertices and its edge midpoints (dense_error.h's point set and its full Newton
// distance); one generator per triangle seeded from `seed` and the triangle's index, so the
// result does not depend on the number of threads. Uses every processor, whatever
// omp_get_max_threads() says (the comparison times its methods on fewer).
double dense_error(const ImplicitSurface& surface, const TriangleSoup& soup, int points_per_face,
                   std::uint64_t seed);

// Share of `before`'s vertices that are still vertices of `after`, recognised by their exact
// position (bitwise): a mesher that keeps a vertex where it was keeps it in this sense, one
// that re-creates every vertex keeps none. 1 for an empty `before`.
double position_survival(const std::vector<Vec3>& before, const std::vector<Vec3>& after);

// One configuration of one method on one scene, over a whole animation.
struct ComparisonRow {
  std::string method;  // "dynamesh" or "openvdb"
  std::string scene;
  double parameter = 0;  // T for dynamesh, the voxel size for OpenVDB
  int frames = 0;
  int threads = 1;
  double triangles_mean = 0, triangles_max = 0;
  double dense_error_max = 0;  // over the measured frames
  // Per frame, medians: the process's CPU time (the work, robust to the other load of a
  // shared machine), the part of it OpenVDB spends sampling F into its grid (0 for
  // dynamesh), and the wall-clock time.
  double cpu_seconds_median = 0, fill_cpu_seconds_median = 0, wall_seconds_median = 0;
  double survival_mean = 0;  // vertices kept from one frame to the next
};

void write_csv_header(std::ostream& out);
void write_csv_row(std::ostream& out, const ComparisonRow& row);
// Parses what write_csv_row wrote (throws std::invalid_argument on a malformed line).
ComparisonRow parse_csv_row(const std::string& line);

// The ratio of `y` at `error` between two curves given as (error, y) points, the second
// interpolated log-log at the first's error; NaN when `error` is outside its range.
double interpolate_log_log(const std::vector<std::array<double, 2>>& curve, double error);

}  // namespace dynamesh::compare
