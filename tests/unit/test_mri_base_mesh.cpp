// The first mesh of an mri layer (mri_base_mesh.h) on closed forms: a spherical shell, whose
// cavity the cuberille fills (its largest piece, cavities filled), must come out with both
// spheres; a ball, which the cuberille has whole, must come out as the cuberille.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/surface/volume/cuberille_base_mesh.h"
#include "core/surface/volume/mri_base_mesh.h"
#include "core/topology/topology_events.h"
#include "tests/support/mesh_validity.h"

namespace dynamesh {
namespace {

// The solid between radii `inner` and `outer` about the origin (inner 0: a ball); F < 0
// inside. Its zero set is the two spheres, the inner one the surface of a cavity.
class Shell final : public ImplicitSurface {
 public:
  Shell(double inner, double outer) : inner_(inner), outer_(outer) {}
  std::string name() const override { return "shell"; }
  Box3 bounds() const override {
    Box3 box;
    box.extend(Vec3::Constant(-outer_ - 2.0));
    box.extend(Vec3::Constant(outer_ + 2.0));
    return box;
  }
  Mesh48 base_mesh() const override { return make_mri_base_mesh(*this, options); }
  double value(const Vec3& p) const override {
    return inner_ > 0 ? std::max(p.norm() - outer_, inner_ - p.norm()) : p.norm() - outer_;
  }
  double value_gradient(const Vec3& p, Vec3& g) const override {
    const double r = p.norm();
    const bool outer = inner_ <= 0 || r - outer_ >= inner_ - r;
    g = (outer ? 1.0 : -1.0) * p / std::max(r, 1e-300);
    return value(p);
  }
  MriBaseMeshOptions options;

 private:
  double inner_, outer_;
};

// Largest distance of a vertex from whichever sphere of the shell is nearer, and how many
// vertices lie on the inner one.
struct OnSpheres {
  double worst = 0.0;
  std::size_t inner = 0;
};
OnSpheres on_spheres(const Mesh48& mesh, double inner, double outer) {
  OnSpheres s;
  for (const Vertex v : mesh.live_vertices()) {
    const double r = mesh.position(v).norm();
    s.worst = std::max(s.worst, std::min(std::abs(r - inner), std::abs(r - outer)));
    s.inner += std::abs(r - inner) < std::abs(r - outer);
  }
  return s;
}

// The cuberille of `shell` at its options' cell size.
Mesh48 cuberille_of(const Shell& shell) {
  CuberilleOptions c;
  c.cell_size = shell.options.cell_size;
  return make_cuberille_base_mesh(shell, shell.bounds(), c);
}

TEST(MriBaseMesh, ShellKeepsTheCavitysSurface) {
  Shell shell(4.0, 9.0);
  shell.options.cell_size = 2.0;
  MriBaseMeshInfo info;
  const Mesh48 mesh = make_mri_base_mesh(shell, shell.options, &info);
  EXPECT_EQ(info.contour_pieces, 2u);
  EXPECT_EQ(info.pieces_added, 1u);
  EXPECT_FALSE(info.contour_whole);
  EXPECT_EQ(summarize_topology(mesh), (MeshTopologySummary{4, 2}));
  const OnSpheres s = on_spheres(mesh, 4.0, 9.0);
  EXPECT_LT(s.worst, 1e-6);
  EXPECT_GT(s.inner, 0u);
  const test::MeshValidity v = test::check_mesh_validity(mesh);
  EXPECT_TRUE(v.embedded_closed_manifold()) << v.describe();
  // The cuberille alone fills the cavity: one sphere.
  const Mesh48 cuberille = cuberille_of(shell);
  EXPECT_EQ(summarize_topology(cuberille), (MeshTopologySummary{2, 1}));
  EXPECT_EQ(on_spheres(cuberille, 4.0, 9.0).inner, 0u);
}

TEST(MriBaseMesh, BallIsTheCuberille) {
  Shell ball(0.0, 9.0);
  ball.options.cell_size = 2.0;
  MriBaseMeshInfo info;
  const Mesh48 mesh = make_mri_base_mesh(ball, ball.options, &info);
  EXPECT_GT(info.coverage, 0.9);
  EXPECT_EQ(info.contour_pieces, 1u);
  EXPECT_TRUE(info.pieces_added == 0 && !info.contour_whole);
  const Mesh48 cuberille = cuberille_of(ball);
  ASSERT_EQ(mesh.n_vertices(), cuberille.n_vertices());
  ASSERT_EQ(mesh.n_faces(), cuberille.n_faces());
  for (const Vertex v : cuberille.live_vertices())
    EXPECT_EQ(mesh.position(v), cuberille.position(v));
}

}  // namespace
}  // namespace dynamesh
