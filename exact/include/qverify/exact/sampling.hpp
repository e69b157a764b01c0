#pragma once
/// \file sampling.hpp
/// Exact, deterministic (seeded) sample points on quadrics and on plane
/// sections of quadrics (the terminator A ∩ polar plane).
///
/// Method: a rational base point b at the object (A's centre, a point of its axis of centres, a point
/// inside a paraboloid on its axis; for a section, the conic's centre, else the foot of that point on
/// the plane: never the world origin, which may be far from the object) and a random
/// rational direction u (inside the plane, for a section); the line b + t u
/// meets A where alpha t^2 + 2 beta t + c = 0, at
///   x = b - (beta/alpha) u +- sqrt(beta^2 - alpha c) (u/alpha),
/// a point of Q(sqrt(delta))^4 (RootPoint). Directions with delta < 0 miss
/// the quadric and are drawn again. The arithmetic is on integers (A, b and u
/// scaled by positive factors, which change neither the quadric nor the line;
/// one gcd per coordinate at the end). A singular section (a line pair, a double
/// line, a single real point) also contributes its exact rational singular
/// point(s), so a terminator that is a single point is still sampled.

#include <qverify/exact/root_point.hpp>

#include <cstdint>
#include <vector>

namespace qverify {

struct SampleReport {
  std::vector<RootPoint> points;
  int attempts = 0;  ///< lines drawn
  bool exhausted = false;  ///< fewer points than asked were found
};

/// Up to n points of A ∩ {pi . x = 0}, all finite.
SampleReport sample_section(const Mat4<Rational>& A, const Vec4<Rational>& pi, int n, std::uint64_t seed);

/// Up to n finite points of A.
SampleReport sample_quadric(const Mat4<Rational>& A, int n, std::uint64_t seed);

}  // namespace qverify
