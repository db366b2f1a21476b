// Orientation of open surfaces, read back from what the real dynamesh-cli exports (issue 12,
// finding 3): a height field y = f(x, z) (the sinc scene, a typed --height-field) faces up,
// its normals have a positive y component everywhere, and the triangles turn the same way as
// the normals (the renderer draws a triangle's front by its winding, the lighting by the
// normals). The typed wobbling tube of assets/examples faces outwards.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli_runner.h"
#include "core/geometry/vector_types.h"
#include "ply_reader.h"

namespace dynamesh {
namespace {

using test::Args;
using test::operator+;

struct Exported {
  std::vector<Vec3> positions, normals;
  std::vector<std::vector<std::uint32_t>> faces;
};

// Step 0 of a run, exported with --export and read back from its PLY file.
Exported export_frame(const Args& args, const std::string& name) {
  const std::filesystem::path dir = test::cli_scratch("orientation_" + name);
  const test::CliRun r =
      test::run_cli(args + Args{"--steps", "0", "--export", dir.string(), "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
  const test::PlyData ply = test::read_ply((dir / "frame_00000.ply").string());
  Exported e;
  const int x = test::ply_column(ply, "x"), nx = test::ply_column(ply, "nx");
  if (x < 0 || nx < 0) return e;
  for (const std::vector<double>& row : ply.vertices) {
    e.positions.emplace_back(row[x], row[x + 1], row[x + 2]);
    e.normals.emplace_back(row[nx], row[nx + 1], row[nx + 2]);
  }
  e.faces = ply.faces;
  EXPECT_GT(e.faces.size(), 100u) << name;
  return e;
}

// Every triangle's geometric normal (from its winding) agrees with its vertices' normals.
void expect_winding_agrees_with_normals(const Exported& e) {
  std::size_t disagreeing = 0;
  for (const auto& f : e.faces) {
    const Vec3 &a = e.positions[f[0]], &b = e.positions[f[1]], &c = e.positions[f[2]];
    const Vec3 face = (b - a).cross(c - a);
    for (const std::uint32_t v : f) disagreeing += !(face.dot(e.normals[v]) > 0.0);
  }
  EXPECT_EQ(disagreeing, 0u) << "of " << 3 * e.faces.size() << " face corners";
}

// A height field: normals up everywhere, and at the vertex nearest the domain's centre.
void expect_faces_up(const Exported& e, const Vec3& centre, double min_ny) {
  ASSERT_FALSE(e.normals.empty());
  std::size_t nearest = 0, down = 0;
  for (std::size_t v = 0; v < e.positions.size(); ++v) {
    const Vec3 d = e.positions[v] - centre, n = e.positions[nearest] - centre;
    if (Vec2(d.x(), d.z()).norm() < Vec2(n.x(), n.z()).norm()) nearest = v;
    down += !(e.normals[v].y() >= min_ny);
  }
  EXPECT_EQ(down, 0u) << "of " << e.normals.size() << " normals with y below " << min_ny;
  EXPECT_GT(e.normals[nearest].y(), 0.99) << "at " << e.positions[nearest].transpose();
  expect_winding_agrees_with_normals(e);
}

TEST(CliOrientation, SincFacesUp) {
  // Flat (alpha = 0): every normal is +y.
  expect_faces_up(export_frame({"--scene", "sinc", "--param", "alpha=0"}, "sinc_flat"),
                  Vec3::Zero(), 1.0 - 1e-6);
  // Curved (t = 0.25, amplitude 0.6): the normal (-f_x, 1, -f_z)/|.| of a height field still
  // has a positive y component everywhere.
  expect_faces_up(export_frame({"--scene", "sinc", "--t0", "0.25"}, "sinc_curved"), Vec3::Zero(),
                  1e-3);
}

TEST(CliOrientation, TypedHeightFieldFacesUpOverItsOwnDomain) {
  // An off-centre domain, longer in z, so that a swap of x and z would show.
  const Args hill{"--scene",  "expr",     "--height-field", "0.3*exp(-4*(x^2+(z-0.5)^2))",
                  "--domain", "-1,1,-1,2"};
  const Exported e = export_frame(hill, "typed_hill");
  expect_faces_up(e, Vec3(0, 0, 0.5), 1e-3);
  Box3 box;
  for (const Vec3& p : e.positions) {
    box.extend(p);
    EXPECT_NEAR(p.y(), 0.3 * std::exp(-4 * (p.x() * p.x() + (p.z() - 0.5) * (p.z() - 0.5))), 1e-6)
        << p.transpose();
  }
  EXPECT_NEAR(box.min.x(), -1.0, 1e-6);
  EXPECT_NEAR(box.max.x(), 1.0, 1e-6);
  EXPECT_NEAR(box.min.z(), -1.0, 1e-6);
  EXPECT_NEAR(box.max.z(), 2.0, 1e-6);
  // f = 0: flat, every normal +y.
  expect_faces_up(
      export_frame({"--scene", "expr", "--height-field", "0*x", "--domain", "-1,1,-1,2"},
                   "typed_flat"),
      Vec3(0, 0, 0.5), 1.0 - 1e-6);
}

TEST(CliOrientation, ExampleWobblingTubeFacesOutwards) {
  std::ifstream in(std::string(DYNAMESH_SOURCE_DIR) + "/assets/examples/wobbling-tube.args");
  Args args;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) args.push_back(line);
  ASSERT_FALSE(args.empty());
  const Exported e = export_frame(args + Args{"--t0", "0.25"}, "tube");
  ASSERT_FALSE(e.normals.empty());
  std::size_t inward = 0;
  for (std::size_t v = 0; v < e.positions.size(); ++v) {
    // Around the y axis: the normal's horizontal part points away from the axis.
    const Vec2 radial(e.positions[v].x(), e.positions[v].z());
    inward += !(Vec2(e.normals[v].x(), e.normals[v].z()).dot(radial) > 0.0);
  }
  EXPECT_EQ(inward, 0u) << "of " << e.normals.size();
  expect_winding_agrees_with_normals(e);
}

}  // namespace
}  // namespace dynamesh
