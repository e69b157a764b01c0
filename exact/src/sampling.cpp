#include <qverify/core/quadric.hpp>
#include <qverify/exact/sampling.hpp>

#include <random>

namespace qverify {
namespace {

using Q = Rational;

struct Draw {
  std::mt19937_64 gen;
  explicit Draw(std::uint64_t seed) : gen(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  Q small() { return Q(std::uniform_int_distribution<int>(-9, 9)(gen)); }
  /// Draws x, then y, then z (sequenced: the order of a call's arguments is
  /// unspecified, and gcc and clang differ, which gave other points per compiler).
  Vec3<Q> vec3() {
    Vec3<Q> v;
    do {
      const Q x = small(), y = small(), z = small();
      v = Vec3<Q>(x, y, z);
    } while (v.isZero());
    return v;
  }
};

/// The base point b of the lines drawn, with A b and b^T A b: computed once per
/// base point, not per line (b has large denominators; u is small).
struct Base {
  Base(const Mat4<Q>& A, const Vec4<Q>& b_) : b(b_), Ab(A * b_), c(b_.dot(Ab)) {}
  Vec4<Q> b, Ab;
  Q c;
};

/// Adds the points where the line b + t u meets A (b finite, u at infinity).
bool intersect_line(const Mat4<Q>& A, const Base& base, const Vec4<Q>& u, std::vector<RootPoint>& out, int want) {
  const Vec4<Q>& b = base.b;
  const Q& c = base.c;
  const Q alpha = u.dot(A * u), beta = u.dot(base.Ab);
  if (alpha == 0) {
    if (beta == 0) return false;
    out.emplace_back(Vec4<Q>(b - (c / (2 * beta)) * u), Vec4<Q>::Zero(), Q(0));  // the one finite root
    return true;
  }
  const Q delta = beta * beta - alpha * c;
  if (delta <= 0) return false;  // misses (or touches) A
  const Vec4<Q> p = b - (beta / alpha) * u, q = u / alpha;
  out.emplace_back(p, q, delta);
  if (static_cast<int>(out.size()) < want) out.emplace_back(p, Vec4<Q>(-q), delta);
  return true;
}

Vec4<Q> finite(const Vec3<Q>& v) { return Vec4<Q>(v(0), v(1), v(2), Q(1)); }

}  // namespace

SampleReport sample_section(const Mat4<Q>& A, const Vec4<Q>& pi, int n, std::uint64_t seed) {
  SampleReport rep;
  const Vec3<Q> normal = pi.head<3>();
  if (normal.isZero() || n <= 0) {
    rep.exhausted = n > 0;
    return rep;
  }
  Draw draw(seed);
  const Eigen::Matrix<Q, 4, 3> E = plane_basis<Q>(pi);
  const Mat3<Q> K = E.transpose() * A * E;
  auto on_plane = [&](const Eigen::Matrix<Q, 3, 1>& s, std::vector<RootPoint>& out) {
    const Vec4<Q> x = E * s;
    if (x(3) != 0 && !x.isZero()) out.emplace_back(Vec4<Q>(x / x(3)), Vec4<Q>::Zero(), Q(0));
  };
  // Singular points of the section (exact, rational).
  const Mat3<Q> adj = adjugate3<Q>(K);
  if (K.determinant() == 0) {
    if (!adj.isZero()) {
      for (int j = 0; j < 3; ++j)
        if (!adj.col(j).isZero()) {
          on_plane(adj.col(j), rep.points);
          break;
        }
    } else if (!K.isZero()) {  // double line r.s = 0
      Eigen::Matrix<Q, 3, 1> r = K.row(0).transpose();
      for (int i = 1; r.isZero() && i < 3; ++i) r = K.row(i).transpose();
      for (int j = 0; j < 3 && static_cast<int>(rep.points.size()) < n; ++j) {
        const Eigen::Matrix<Q, 3, 1> k = r.cross(Eigen::Matrix<Q, 3, 1>::Unit(j));
        if (!k.isZero()) on_plane(k, rep.points);
      }
    }
  }
  // Base point: the centre of the section (pole of its line at infinity), else a point of the plane.
  Vec4<Q> b = Vec4<Q>::Zero();
  if (K.determinant() != 0) {
    const Eigen::Matrix<Q, 3, 1> ell = E.transpose() * Vec4<Q>(0, 0, 0, 1);
    const Vec4<Q> c = E * Eigen::Matrix<Q, 3, 1>(adj * ell);
    if (c(3) != 0) b = c / c(3);
  }
  if (b(3) == 0) {  // the foot of the origin on the plane
    b = finite(Vec3<Q>(-(pi(3) / normal.squaredNorm()) * normal));
  }
  const int max_attempts = 50 * n + 50;
  Base base(A, b);
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    ++rep.attempts;
    const Vec3<Q> d = normal.cross(draw.vec3());  // a direction inside the plane
    if (d.isZero()) continue;
    intersect_line(A, base, Vec4<Q>(d(0), d(1), d(2), Q(0)), rep.points, n);
    if (rep.attempts % 8 == 0 && rep.points.empty()) {  // move the base point within the plane
      const Vec3<Q> shift = normal.cross(draw.vec3());
      b.head<3>() += shift;
      base = Base(A, b);
    }
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

SampleReport sample_quadric(const Mat4<Q>& A, int n, std::uint64_t seed) {
  SampleReport rep;
  if (n <= 0) return rep;
  Draw draw(seed);
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  const Vec3<Q> k = A.topRightCorner<3, 1>();
  Vec4<Q> b = finite(Vec3<Q>::Zero());
  if (K.determinant() != 0) b = finite(Vec3<Q>(-(K.inverse() * k)));  // centre
  const int max_attempts = 50 * n + 50;
  Base base(A, b);
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    ++rep.attempts;
    const Vec3<Q> d = draw.vec3();
    intersect_line(A, base, Vec4<Q>(d(0), d(1), d(2), Q(0)), rep.points, n);
    if (rep.attempts % 8 == 0 && rep.points.empty()) {
      b.head<3>() += draw.vec3();
      base = Base(A, b);
    }
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

}  // namespace qverify
