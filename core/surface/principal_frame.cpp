#include "core/surface/principal_frame.h"

#include <Eigen/Eigenvalues>

namespace dynamesh {

PrincipalCurvatures principal_curvatures_in_frame(const Mat2& shape, const Vec3& e1, const Vec3& e2,
                                                  const Vec3& normal) {
  // The closed-form 2x2 solver allocates nothing; its eigenvalues come in increasing order.
  Eigen::SelfAdjointEigenSolver<Mat2> solver;
  solver.computeDirect(0.5 * (shape + shape.transpose()));
  const Vec2 a1 = solver.eigenvectors().col(1);
  PrincipalCurvatures pc;
  pc.k1 = solver.eigenvalues()(1);
  pc.k2 = solver.eigenvalues()(0);
  pc.normal = normal;
  pc.dir1 = (a1(0) * e1 + a1(1) * e2).normalized();
  pc.dir2 = normal.cross(pc.dir1);
  return pc;
}

}  // namespace dynamesh
