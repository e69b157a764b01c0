// A user's own implementation of the two transforms, as a renderer would
// write it: one right version and one with a plausible slip each, to show the
// matchers telling them apart. Plain Eigen, no qverify.
#pragma once
#include <Eigen/Core>

namespace mine {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;

/// The shadow cone of x^T A x = 0 from the light L: (L^T A L) A - (A L)(A L)^T.
inline Mat4 shadow_cone(const Mat4& A, const Vec4& L) {
  const Vec4 AL = A * L;
  return L.dot(AL) * A - AL * AL.transpose();
}

/// The slip: the rank-one term added instead of subtracted. It still vanishes
/// on the terminator (every point there has (A L).x = 0 and x^T A x = 0), so
/// a test that only samples the terminator passes it; it is no cone from L.
inline Mat4 shadow_cone_with_slip(const Mat4& A, const Vec4& L) {
  const Vec4 AL = A * L;
  return L.dot(AL) * A + AL * AL.transpose();
}

/// The reflection in the plane n.x + d = 0 (p = (n, d)): x - 2 (n.x + d) n / (n.n).
inline Mat4 mirror(const Vec4& p) {
  const double nn = p.head<3>().squaredNorm();
  Mat4 M = Mat4::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) M(i, j) -= 2 * p(i) * p(j) / nn;
  return M;
}

/// The mirror image of A: B = M^T A M (M is its own inverse).
inline Mat4 mirror_image(const Mat4& A, const Vec4& p) {
  const Mat4 M = mirror(p);
  return M.transpose() * A * M;
}

/// The slip: M A M^T, the same as M^T A M only for a mirror through the origin.
inline Mat4 mirror_image_with_slip(const Mat4& A, const Vec4& p) {
  const Mat4 M = mirror(p);
  return M * A * M.transpose();
}

}  // namespace mine
