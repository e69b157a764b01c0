// The inputs both example test suites use (Catch2 and GoogleTest).
#pragma once
#include <qverify/core/quadric.hpp>

namespace fixtures {
// An ellipsoid (semi-axes 1, 2, 3) centred at (1, 2, 3): x^T A x = 0.
inline Eigen::Matrix4d ellipsoid() {
  return qverify::ellipsoid_quadric<double>(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity());
}
inline const Eigen::Vector4d lamp(4, 5, 12, 1);          // a point light (x, y, z, 1)
inline const Eigen::Vector4d sun(-1, -2, -10, 0);        // a parallel light (direction, 0)
inline const Eigen::Vector4d floor_mirror(0, 0, 1, 2);   // the mirror z = -2
}  // namespace fixtures
