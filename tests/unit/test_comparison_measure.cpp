// The re-meshing comparison's measurements (bench/comparison_measure.h, issue 17): the dense
// error of a triangle soup against closed forms, vertex survival, the CSV the plots read and
// the log-log interpolation of its summary; and, where OpenVDB is installed, a tiny run of
// bench/compare_openvdb itself.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bench/comparison_measure.h"
#include "cli_runner.h"
#include "core/surface/scene_registry.h"

namespace dynamesh {
namespace {

std::unique_ptr<ImplicitSurface> unit_sphere() {
  std::unique_ptr<Surface> s = make_scene("sphere");
  s->set_parameter("R0", 1.0);
  s->set_parameter("R1", 1.0);
  s->set_time(0.0);
  return std::unique_ptr<ImplicitSurface>(dynamic_cast<ImplicitSurface*>(s.release()));
}

// The octahedron inscribed in the unit sphere: its worst point is a face centroid, at
// 1 - 1/sqrt(3) from the sphere; its vertices are on it and its edge midpoints at
// 1 - 1/sqrt(2), so a measurement that skipped the random points would fail.
compare::TriangleSoup octahedron() {
  compare::TriangleSoup s;
  s.points = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
              -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  for (std::uint32_t x : {0u, 1u})
    for (std::uint32_t y : {2u, 3u})
      for (std::uint32_t z : {4u, 5u}) s.triangles.push_back({x, y, z});
  return s;
}

TEST(ComparisonMeasure, DenseErrorOfTheInscribedOctahedronIsItsCentroidDistance) {
  const auto sphere = unit_sphere();
  const double exact = 1.0 - 1.0 / std::sqrt(3.0);
  const double measured = compare::dense_error(*sphere, octahedron(), 4000, 1);
  EXPECT_LE(measured, exact + 1e-9);
  EXPECT_GT(measured, exact - 1e-3);
  // Shrunk by 1/sqrt(3): its centroids lie at 1/3 from the centre, 2/3 inside the sphere.
  compare::TriangleSoup small = octahedron();
  for (Vec3& p : small.points) p /= std::sqrt(3.0);
  EXPECT_NEAR(compare::dense_error(*sphere, small, 4000, 2), 1.0 - 1.0 / 3.0, 1e-3);
}

TEST(ComparisonMeasure, PositionSurvivalCountsExactlyKeptVertices) {
  const std::vector<Vec3> before = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::vector<Vec3> after = before;
  EXPECT_DOUBLE_EQ(compare::position_survival(before, after), 1.0);
  after[1].x() = std::nextafter(1.0, 2.0);  // one ulp away: a different vertex
  after.push_back(Vec3(5, 5, 5));
  EXPECT_DOUBLE_EQ(compare::position_survival(before, after), 0.75);
  EXPECT_DOUBLE_EQ(compare::position_survival(before, {}), 0.0);
}

TEST(ComparisonMeasure, CsvRowsReadBackAsWritten) {
  compare::ComparisonRow r{"openvdb", "twist",        0.014,   100, 1,   134492.5,
                           140060,    0.000712345678, 0.81234, 0.5, 0.9, 0.0021};
  std::ostringstream out;
  compare::write_csv_header(out);
  compare::write_csv_row(out, r);
  std::istringstream in(out.str());
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  EXPECT_EQ(header.substr(0, 24), "method,scene,parameter,f");
  const compare::ComparisonRow back = compare::parse_csv_row(line);
  EXPECT_EQ(back.method, r.method);
  EXPECT_EQ(back.scene, r.scene);
  EXPECT_DOUBLE_EQ(back.parameter, r.parameter);
  EXPECT_EQ(back.frames, r.frames);
  EXPECT_EQ(back.threads, r.threads);
  EXPECT_DOUBLE_EQ(back.cpu_seconds_median, r.cpu_seconds_median);
  EXPECT_DOUBLE_EQ(back.fill_cpu_seconds_median, r.fill_cpu_seconds_median);
  EXPECT_DOUBLE_EQ(back.wall_seconds_median, r.wall_seconds_median);
  EXPECT_DOUBLE_EQ(back.triangles_mean, r.triangles_mean);
  EXPECT_NEAR(back.dense_error_max, r.dense_error_max, 1e-14);
  EXPECT_DOUBLE_EQ(back.survival_mean, r.survival_mean);
  EXPECT_THROW(compare::parse_csv_row("openvdb,twist,0.014"), std::invalid_argument);
  EXPECT_THROW(compare::parse_csv_row("a,b,x,1,1,2,3,4,5,6,7,8"), std::invalid_argument);
}

TEST(ComparisonMeasure, LogLogInterpolationIsExactOnAPowerLaw) {
  std::vector<std::array<double, 2>> curve;
  for (double e : {4e-3, 1e-3, 2.5e-4}) curve.push_back({e, 10.0 / (e * e)});
  EXPECT_NEAR(compare::interpolate_log_log(curve, 2e-3) / (10.0 / 4e-6), 1.0, 1e-12);
  EXPECT_NEAR(compare::interpolate_log_log(curve, 5e-4) / (10.0 / 25e-8), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(compare::interpolate_log_log(curve, 1e-2)));
}

#ifdef DYNAMESH_COMPARE_OPENVDB
// The program end to end, tiny: both methods on the capsule, two frames. Its CSV has one row
// each; dynamesh's error is within the adapter's band, OpenVDB's mesh is not empty and keeps
// (almost) no vertex; a bad option is one line on stderr and exit status 2.
TEST(ComparisonProgram, WritesOneRowPerConfigurationAndRefusesBadOptions) {
  const auto dir = test::cli_scratch("compare_openvdb");
  const std::string csv = (dir / "c.csv").string();
  const std::string command = test::shell_quoted(DYNAMESH_COMPARE_OPENVDB) +
                              " --scenes capsule-bend --thresholds 0.004 --voxels 0.04"
                              " --frames 2 --measure-every 1 --out " +
                              test::shell_quoted(csv) + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<compare::ComparisonRow> rows;
  while (std::getline(in, line)) rows.push_back(compare::parse_csv_row(line));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].method, "dynamesh");
  EXPECT_GT(rows[0].dense_error_max, 0.0);
  EXPECT_LE(rows[0].dense_error_max, 1.10 * 1.25 * 0.004);
  EXPECT_GT(rows[0].survival_mean, 0.5);
  EXPECT_EQ(rows[1].method, "openvdb");
  EXPECT_GT(rows[1].triangles_mean, 1000.0);
  EXPECT_LT(rows[1].survival_mean, 0.05);

  const std::string err = (dir / "bad.err").string();
  const int raw = std::system((test::shell_quoted(DYNAMESH_COMPARE_OPENVDB) +
                               " --voxels 0.04,-1 2> " + test::shell_quoted(err))
                                  .c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 2);
  const std::string message = test::slurp_file(err);
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  EXPECT_NE(message.find("--voxels"), std::string::npos) << message;
}
#endif

}  // namespace
}  // namespace dynamesh
