// Typed surfaces (issue 8), without adaptation: formulas against closed forms, thread-safe
// evaluation, clear errors for bad formulas, options and base-mesh files, the guards at
// construction and at set_time(), the periodic grid and the mesh file readers.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/surface/expression/expression.h"
#include "core/surface/expression/height_expression_surface.h"
#include "core/surface/expression/implicit_expression_surface.h"
#include "core/surface/expression/parametric_expression_surface.h"
#include "core/surface/expression/periodic_grid_mesh.h"
#include "core/surface/expression/triangle_mesh_file.h"
#include "core/surface/scene_registry.h"
#include "core/surface/scenes/sinc_scene.h"
#include "mesh_measure.h"

namespace dynamesh {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(DYNAMESH_BINARY_DIR) / "test_scratch" /
                       ("expr_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The message of the std::invalid_argument that `fn` throws ("" if none).
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_ERROR_HAS(call, text)                                                 \
  do {                                                                               \
    const std::string message = error_of([&] { (void)(call); });                     \
    EXPECT_NE(message.find(text), std::string::npos)                                 \
        << "message: '" << message << "', expected '" << text << "'";                \
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message; \
  } while (0)

std::unique_ptr<Surface> expr(const TextOptions& options) {
  return make_scene("expr", {}, options);
}

TEST(ExprFormula, EvaluatesClosedForms) {
  const Expression e({"x^2 + 2*y - sin(z)*t", "pi*e", "x > 0 ? sqrt(x) : -1"}, {"x", "y", "z", "t"},
                     "test formula");
  const double in[4] = {1.5, -0.25, 0.7, 2.0};
  double out[3];
  e.evaluate(in, out);
  EXPECT_DOUBLE_EQ(out[0], 1.5 * 1.5 - 0.5 - std::sin(0.7) * 2.0);
  EXPECT_DOUBLE_EQ(out[1], std::numbers::pi * std::numbers::e);
  EXPECT_DOUBLE_EQ(out[2], std::sqrt(1.5));
  EXPECT_DOUBLE_EQ(e.value(in), out[0]);
}

TEST(ExprFormula, ThreadsEvaluateIndependently) {
  // Every thread evaluates its own points at once; muparser shares nothing between them, so
  // each result must equal the closed form exactly (same operations, same rounding).
  const Expression e({"x*y + cos(x) - y^3"}, {"x", "y"}, "test formula");
  constexpr int kN = 20000;
  std::vector<double> got(kN);
#pragma omp parallel for num_threads(4)
  for (int i = 0; i < kN; ++i) {
    const double in[2] = {0.001 * i, -0.0005 * i};
    got[static_cast<std::size_t>(i)] = e.value(in);
  }
  for (int i = 0; i < kN; ++i) {
    const double x = 0.001 * i, y = -0.0005 * i;
    ASSERT_NEAR(got[static_cast<std::size_t>(i)], x * y + std::cos(x) - y * y * y,
                1e-12 * (1 + std::abs(y * y * y)))
        << "point " << i;
  }
}

TEST(ExprFormula, BadFormulasGiveClearErrors) {
  const std::vector<std::string> xyz{"x", "y", "z", "t"};
  EXPECT_ERROR_HAS(Expression({"x^2 + * y"}, xyz, "implicit formula"),
                   "implicit formula 'x^2 + * y'");
  EXPECT_ERROR_HAS(Expression({"sin(x"}, xyz, "implicit formula"), "implicit formula");
  EXPECT_ERROR_HAS(Expression({"x + w"}, xyz, "implicit formula"),
                   "unknown name 'w' at position 5");
  EXPECT_ERROR_HAS(Expression({"x + w"}, xyz, "implicit formula"), "the variables are x, y, z, t");
  EXPECT_ERROR_HAS(Expression({"   "}, xyz, "implicit formula"), "is empty");
  EXPECT_ERROR_HAS(Expression({"x, y"}, xyz, "implicit formula"), "one formula expected");
  // A height field has no y.
  EXPECT_ERROR_HAS(expr({{"height", "x + y"}}), "unknown name 'y'");
  EXPECT_ERROR_HAS(expr({{"parametric", "u; v"}, {"domain", "0,1,0,1"}}), "three formulas");
}

TEST(ExprFormula, BadOptionsGiveClearErrors) {
  EXPECT_ERROR_HAS(expr({{"bounds", "-1,-1,-1,1,1,1"}}), "no formula given");
  // No options at all: the default formula (a scene menu can always show the scene).
  EXPECT_EQ(expr({})->kind(), SurfaceKind::kImplicit);
  EXPECT_ERROR_HAS(expr({{"implicit", "x"}, {"height", "x"}}), "only one of");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2-1"}}), "--implicit needs --bounds");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2-1"}, {"bounds", "-2,-2,-2,2,-2,2"}}),
                   "is empty along y");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2-1"}, {"bounds", "-2,-2,-2,2,2"}}),
                   "expects 6 numbers");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2-1"}, {"bounds", "-2,a,-2,2,2,2"}}),
                   "--bounds expects");
  EXPECT_ERROR_HAS(expr({{"height", "x"}, {"domain", "1,1,0,1"}}), "--domain 1,1,0,1 is empty");
  EXPECT_ERROR_HAS(expr({{"height", "x"}, {"periodic", "u"}}), "--periodic is for --parametric");
  EXPECT_ERROR_HAS(expr({{"parametric", "u;v;0"}, {"domain", "0,1,0,1"}, {"periodic", "w"}}),
                   "--periodic expects u, v, uv");
  EXPECT_ERROR_HAS(expr({{"parametric", "u;v;0"}}), "--parametric needs --domain");
  EXPECT_ERROR_HAS(expr({{"height", "x"}, {"volume", "a.nii"}}), "takes no option 'volume'");
  // Constant formulas are accepted where numbers are.
  auto tube =
      expr({{"parametric", "cos(u);v;sin(u)"}, {"domain", "0,2*pi,-1,1"}, {"periodic", "u"}});
  EXPECT_DOUBLE_EQ(dynamic_cast<ParametricSurface&>(*tube).domain().max.x(), 2 * std::numbers::pi);
}

TEST(ExprFormula, GuardsRejectNanNoCrossingAndEscapes) {
  const std::string box = "-2,-2,-2,2,2,2";
  // sqrt of a negative number inside the bounds.
  EXPECT_ERROR_HAS(expr({{"implicit", "sqrt(1 - x) - 0.5"}, {"bounds", box}}), "is NaN at (");
  // 1/0 at the centre of the grid.
  EXPECT_ERROR_HAS(expr({{"implicit", "1 - 1/(x^2+y^2+z^2)"}, {"bounds", box}}),
                   "is infinite at (0, 0, 0)");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2+1"}, {"bounds", box}}), "no zero crossing");
  EXPECT_ERROR_HAS(expr({{"implicit", "x^2+y^2+z^2-9"}, {"bounds", box}}),
                   "on the side of --bounds");
  // F > 0 inside: negative on the sides, the hint says to negate.
  EXPECT_ERROR_HAS(expr({{"implicit", "1 - x^2-y^2-z^2"}, {"bounds", box}}), "negate F");
  EXPECT_ERROR_HAS(expr({{"height", "log(x)"}}), "height formula 'log(x)' is not finite at (");
  EXPECT_ERROR_HAS(expr({{"parametric", "u;v;1/u"}, {"domain", "0,1,0,1"}}),
                   "is not finite at (0, 0)");
  EXPECT_ERROR_HAS(
      expr({{"parametric", "cos(u);v;sin(u)"}, {"domain", "0,6.28,-1,1"}, {"periodic", "u"}}),
      "is not periodic in u");
}

TEST(ExprFormula, SetTimeRejectsFormulaThatBreaksLaterAndKeepsTime) {
  // Fine at t = 0; NaN for t > 0.5 (sqrt of a negative), no zero crossing at t = 0.3 (radius
  // 0.4 - 1.2 t goes negative at t = 1/3).
  auto nan_later = expr({{"implicit", "sqrt(x^2+y^2+z^2) - 0.5 + sqrt(0.5 - t) - sqrt(0.5)"},
                         {"bounds", "-1,-1,-1,1,1,1"}});
  nan_later->set_time(0.25);
  EXPECT_ERROR_HAS(nan_later->set_time(0.75), "is NaN at");
  EXPECT_EQ(nan_later->time(), 0.25);
  auto vanishing =
      expr({{"implicit", "sqrt(x^2+y^2+z^2) - (0.4 - 1.2*t)"}, {"bounds", "-1,-1,-1,1,1,1"}});
  EXPECT_ERROR_HAS(vanishing->set_time(0.5), "no zero crossing inside --bounds at t = 0.5");
  auto height = expr({{"height", "1/(t - 0.5)"}});
  EXPECT_ERROR_HAS(height->set_time(0.5), "is not finite");
  EXPECT_EQ(height->time(), 0.0);
}

TEST(ExprFormula, ImplicitDerivativesMatchClosedForms) {
  // Sphere of radius 0.7: grad = p/|p|, curvatures 1/0.7.
  auto s = expr({{"implicit", "sqrt(x^2+y^2+z^2) - 0.7"}, {"bounds", "-1,-1,-1,1,1,1"}});
  const auto& f = dynamic_cast<const ImplicitSurface&>(*s);
  const Vec3 p = Vec3(0.3, -0.5, 0.4).normalized() * 0.7;
  Vec3 g;
  EXPECT_NEAR(f.value_gradient(p, g), 0.0, 1e-15);
  // Central differences, h = 1e-5 * diagonal: truncation |F'''| h^2 / 6 ~ 1e-10.
  EXPECT_NEAR((g - p / 0.7).norm(), 0.0, 1e-8);
  const PrincipalCurvatures k = f.curvatures(p);
  // Second differences, H = 1e-4 * diagonal: truncation ~1e-7, rounding eps/H^2 ~ 1e-8.
  EXPECT_NEAR(k.k1, 1 / 0.7, 1e-5);
  EXPECT_NEAR(k.k2, 1 / 0.7, 1e-5);
}

TEST(ExprFormula, HeightMatchesBuiltInSinc) {
  SincScene sinc;
  auto typed = expr({{"height",
                      "0.6*sin(2*pi*t)*(sqrt(x^2+z^2) < 1e-9 ? 1 : "
                      "sin(4*pi*sqrt(x^2+z^2))/(4*pi*sqrt(x^2+z^2)))*exp(-0.5*sqrt(x^2+z^2))"}});
  sinc.set_time(0.3);
  typed->set_time(0.3);
  const auto& h = dynamic_cast<const ParametricSurface&>(*typed);
  for (const Vec2& uv : {Vec2(0.3, 0.2), Vec2(-0.7, 0.55), Vec2(0.9, -0.9)}) {
    EXPECT_NEAR((h.position(uv) - sinc.position(uv)).norm(), 0.0, 1e-14);
    const ParametricDerivatives a = h.derivatives(uv), b = sinc.derivatives(uv);
    // First derivatives: truncation f''' h^2/6 with h = 2e-5 and |f'''| ~ (4 pi)^3 0.6: ~1e-7.
    EXPECT_NEAR((a.su - b.su).norm(), 0.0, 1e-6);
    EXPECT_NEAR((a.sv - b.sv).norm(), 0.0, 1e-6);
    // Second: truncation f'''' H^2/12 with H = 2e-4, |f''''| ~ (4 pi)^4 0.6: ~5e-5.
    EXPECT_NEAR((a.suu - b.suu).norm(), 0.0, 1e-3 * (1 + b.suu.norm()));
    EXPECT_NEAR((a.suv - b.suv).norm(), 0.0, 1e-3 * (1 + b.suv.norm()));
    // Same orientation as sinc: Su x Sv points up, to +y.
    EXPECT_GT(h.normal(uv).y(), 0.0);
  }
}

TEST(ExprFormula, PeriodicGridClosesAlongPeriodicDirections) {
  const double two_pi = 2 * std::numbers::pi;
  const Mesh48 cylinder = make_periodic_grid_mesh(8, 4, Vec2(0, -1), Vec2(two_pi, 1), true, false);
  ASSERT_TRUE(cylinder.check().ok()) << cylinder.check().summary();
  test::Topology t = test::topology(cylinder);
  EXPECT_EQ(t.euler(), 0);             // an annulus
  EXPECT_EQ(t.boundary_edges, 2 * 8);  // the two ends only
  const Mesh48 torus = make_periodic_grid_mesh(8, 6, Vec2(0, 0), Vec2(two_pi, two_pi), true, true);
  ASSERT_TRUE(torus.check().ok()) << torus.check().summary();
  t = test::topology(torus);
  EXPECT_EQ(t.euler(), 0);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.vertices, 8 * 6);
  EXPECT_ERROR_HAS(make_periodic_grid_mesh(3, 4, Vec2(0, 0), Vec2(1, 1), true, false),
                   "even count >= 4");
}

TEST(ExprFormula, MeshFilesReadAndRejectBrokenOnes) {
  const fs::path dir = scratch("mesh_files");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  };
  // A tetrahedron in ascii PLY with an extra property and a quad-free face list.
  const std::string tetra_ply = write("tetra.ply",
                                      "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\n"
                                      "property float x\nproperty float y\nproperty float z\n"
                                      "property uchar red\nelement face 4\n"
                                      "property list uchar int vertex_indices\nend_header\n"
                                      "0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  TriangleMesh m = read_triangle_mesh(tetra_ply);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.positions[3], Vec3(0, 0, 1));
  // The same in binary little endian, with double coordinates and a quad fanned in two.
  std::string bin =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\n"
      "property double y\nproperty double z\nelement face 1\nproperty list uchar uint "
      "vertex_indices\nend_header\n";
  for (double c : {0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.})
    bin.append(reinterpret_cast<const char*>(&c), 8);
  bin.push_back(4);
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) bin.append(reinterpret_cast<const char*>(&i), 4);
  m = read_triangle_mesh(write("quad.ply", bin));
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  m = read_triangle_mesh(write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n"));
  EXPECT_EQ(m.triangles.size(), 2u);

  EXPECT_ERROR_HAS(read_triangle_mesh((dir / "missing.obj").string()), "no such file");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("a.stl", "solid")), "use a .obj or .ply");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("b.ply", "plx\n")), "not a PLY file");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("c.ply",
                                            "ply\nformat ascii 1.0\nelement vertex 3\n"
                                            "property float x\nproperty float y\n"
                                            "property float z\nend_header\n0 0 0\n1 0\n")),
                   "ends early");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")),
                   "base mesh");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("e.obj", "v 0 0 0\n")), "holds no faces");
  EXPECT_ERROR_HAS(read_triangle_mesh(write("f.ply",
                                            "ply\nformat ascii 1.0\nelement vertex 1\n"
                                            "property float x\nproperty float y\n"
                                            "property float z\nelement face 1\nproperty "
                                            "list uchar int vertex_indices\nend_header\n"
                                            "0 0 0\n3 0 0 5\n")),
                   "refers to vertex 5 of 1");

  // Non-manifold: three triangles on one edge (a "book"), projected onto a sphere.
  const std::string book = write("book.obj",
                                 "v 0 0 0.5\nv 0 0 -0.5\nv 0.5 0 0\nv -0.5 0 0\nv 0 0.5 0\n"
                                 "f 1 2 3\nf 2 1 4\nf 1 2 5\n");
  EXPECT_ERROR_HAS(expr({{"implicit", "sqrt(x^2+y^2+z^2) - 0.5"},
                         {"bounds", "-1,-1,-1,1,1,1"},
                         {"base-mesh", book}}),
                   "manifold");
}

TEST(ExprFormula, BaseMeshFarFromTheSurfaceOrFoldedIsRejected) {
  // The torus base mesh on a surface of sphere topology: its faces turn over.
  const std::string torus = std::string(DYNAMESH_SOURCE_DIR) + "/assets/examples/torus.obj";
  EXPECT_ERROR_HAS(expr({{"implicit", "sqrt(x^2+y^2+z^2) - 1.2"},
                         {"bounds", "-2,-2,-2,2,2,2"},
                         {"base-mesh", torus}}),
                   "folds over");
  // (A torus formula without a base mesh is no longer refused: it is contoured from F,
  // tests/unit/test_topology_contour.cpp.)
}

}  // namespace
}  // namespace dynamesh
