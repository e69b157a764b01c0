#pragma once
// Laws of the transforms, written once as templated checkers and run for every
// scalar type of the ladder on random, near-degenerate and special inputs.
// For exact types every tolerance is zero: the laws are checked as identities.
#include <qverify/core/core.hpp>
#include <qverify/exact/rounding.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>

namespace qverify::test {

/// x^T diag(d) x + 2 (v . x) + c, as a matrix.
inline Mat4<Rational> quadric_of(const Vec3<Rational>& d, const Vec3<Rational>& v, const Rational& c) {
  Mat4<Rational> A = Mat4<Rational>::Zero();
  for (int i = 0; i < 3; ++i) A(i, i) = d(i), A(i, 3) = A(3, i) = v(i);
  A(3, 3) = c;
  return A;
}

/// 2^e and 10^e as exact rationals (scales, units and exponents of the sweeps).
inline Rational pow2(int e) {
  using boost::multiprecision::mpz_int;
  return e >= 0 ? Rational(mpz_int(1) << e) : Rational(1) / Rational(mpz_int(1) << -e);
}
inline Rational pow10(int e) {
  boost::multiprecision::mpz_int p = 1;
  for (int k = 0; k < std::abs(e); ++k) p *= 10;
  return e >= 0 ? Rational(p) : Rational(1) / Rational(p);
}

/// A double with a full 53-bit significand and |x| in [2^e, 2^(e+1)), e uniform in
/// [-spread, spread] ("double-valued" inputs: what another program computed).
inline double random_double(std::mt19937_64& g, int spread = 30) {
  const std::uint64_t m = (g() >> 11) | (std::uint64_t(1) << 52);
  const int e = static_cast<int>(g() % static_cast<std::uint64_t>(2 * spread + 1)) - spread;
  const double x = std::ldexp(static_cast<double>(m), e - 52);
  return (g() & 1) ? -x : x;
}

/// Relative tolerance of the law checks: 2^12 eps (0 for exact types).
template <class S> S law_tol() { return S(4096) * Eigen::NumTraits<S>::epsilon(); }

/// Deterministic random small rationals p/q, |p| <= 20, 1 <= q <= 9.
struct RandomRationals {
  std::mt19937_64 gen;
  explicit RandomRationals(std::uint64_t seed) : gen(seed) {}
  Rational next() {
    std::uniform_int_distribution<int> p(-20, 20), q(1, 9);
    return Rational(p(gen)) / Rational(q(gen));
  }
  Mat4<Rational> symmetric() {
    Mat4<Rational> A;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) A(i, j) = A(j, i) = next();
    return A;
  }
  Vec4<Rational> vec4() { return Vec4<Rational>(next(), next(), next(), next()); }
};

/// Rounds an exact matrix to S entry by entry (once, to nearest).
template <class S, int R, int C> Eigen::Matrix<S, R, C> to_scalar(const Eigen::Matrix<Rational, R, C>& m) {
  Eigen::Matrix<S, R, C> out;
  RoundingReport rep;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = round_rational<S>(m(i), rep);
  return out;
}

/// x^T Q x relative to |Q| |x|^2.
template <class S> S incidence(const Mat4<S>& Q, const Vec4<S>& x) {
  const S scale = max_abs(Q) * max_abs(x) * max_abs(x);
  if (scale == S(0)) return S(0);
  return abs_of<S>(S(x.dot(Q * x))) / scale;
}

// ------------------------------------------------------------------ the laws

/// Symmetry preserved: P, R and B are symmetric whenever A is.
template <class S> void law_symmetry(const Mat4<S>& A, const Vec4<S>& L, const Vec4<S>& plane, Method m) {
  const auto sh = shadow<S>(A, L, m);
  CHECK(is_symmetric<S>(sh.P, law_tol<S>()));
  CHECK(is_symmetric<S>(sh.R, law_tol<S>()));
  const auto B = reflection<S>(A, mirror_matrix<S>(plane), m).B;
  CHECK(is_symmetric<S>(B, law_tol<S>()));
}

/// M M = I (eq. (11): M = M^{-1}), and M fixes every point of its plane.
template <class S> void law_mirror_involution(const Vec4<S>& plane, const Vec4<S>& point_on_plane) {
  const Mat4<S> M = mirror_matrix<S>(plane);
  CHECK(max_abs(Mat4<S>(M * M - Mat4<S>::Identity())) <= law_tol<S>());
  CHECK(max_abs(Vec4<S>(M * point_on_plane - point_on_plane)) <= law_tol<S>() * max_abs(point_on_plane));
  CHECK(M(3, 0) == S(0));
  CHECK(M(3, 1) == S(0));
  CHECK(M(3, 2) == S(0));
  CHECK(M(3, 3) == S(1));
}

/// Incidence preserved by reflection: x on A  =>  M x on B.
template <class S> void law_reflection_incidence(const Mat4<S>& A, const Vec4<S>& plane, const Vec4<S>& x_on_A, Method m) {
  const Mat4<S> M = mirror_matrix<S>(plane);
  const Mat4<S> B = reflection<S>(A, M, m).B;
  CHECK(incidence<S>(B, Vec4<S>(M * x_on_A)) <= law_tol<S>());
  CHECK(incidence<S>(reflection_in_plane<S>(A, plane, m).B, Vec4<S>(M * x_on_A)) <= law_tol<S>());
}

/// Terminator incidence: a point x on A and on the polar plane lies on P and R;
/// the light is the apex of P (P L = 0).
template <class S> void law_terminator(const Mat4<S>& A, const Vec4<S>& L, const Vec4<S>& x, Method m) {
  const auto sh = shadow<S>(A, L, m);
  CHECK(incidence<S>(A, x) <= law_tol<S>());
  CHECK(incidence<S>(sh.P, x) <= law_tol<S>());
  CHECK(incidence<S>(sh.R, x) <= law_tol<S>());
  CHECK(max_abs(Vec4<S>(sh.P * L)) <= law_tol<S>() * max_abs(sh.P) * max_abs(L));
}

/// The two routes agree: P and the polar plane up to a positive factor, R up
/// to a non-zero factor, B equal (the same M).
template <class S> void law_routes_agree(const Mat4<S>& A, const Vec4<S>& L, const Vec4<S>& plane) {
  const auto d = shadow<S>(A, L, Method::direct);
  // the direct R forms only the terms of pi h^T + h pi^T without a zero factor of h: the same plane
  // pair, entry for entry (-0 == +0), for every light
  CHECK((d.R.array() == plane_pair<S>(d.polar_plane, frame_plane<S>(L)).array()).all());
  const auto p = shadow<S>(A, L, Method::paper);
  if (p.has(ShadowFlag::singular_frame)) return;  // paper falls back to direct there
  CHECK(proportional(p.P, d.P, Factor::positive, law_tol<S>()));
  CHECK(proportional(p.polar_plane, d.polar_plane, Factor::positive, law_tol<S>()));
  CHECK(proportional(p.R, d.R, Factor::nonzero, law_tol<S>()));
  // eq. (4) as printed is the tangent cone in the frame of C: D = a3 C - (C e3)(C e3)^T
  const Mat4<S>& C = p.paper.C;
  CHECK(proportional(p.paper.D, tangent_cone<S>(C, Vec4<S>(S(0), S(0), S(1), S(0))), Factor::positive, law_tol<S>()));
  const Mat4<S> M = mirror_matrix<S>(plane);
  CHECK(proportional(reflection<S>(A, M, Method::paper).B, reflection<S>(A, M, Method::direct).B, Factor::positive,
                     law_tol<S>()));
  // the rank-one form of (11) is the same B (exactly, for exact types)
  CHECK(proportional(mirror_image_of_plane<S>(A, plane), mirror_image<S>(A, M), Factor::positive, law_tol<S>()));
}

// ------------------------------------------------------------ input families

/// A random exact case with a terminator point: quadric A, light L, and x with
/// x^T A x = 0 and (A L).x = 0 (two entries of A adjusted exactly), a mirror
/// plane and a point on it.
struct ExactCase {
  Mat4<Rational> A;
  Vec4<Rational> L, x, plane, on_plane;
  bool on_terminator = true;  ///< x also lies on the polar plane of L
};

inline ExactCase random_case(RandomRationals& rng, bool parallel_light) {
  ExactCase c;
  c.A = rng.symmetric();
  c.L = rng.vec4();
  c.L(3) = parallel_light ? Rational(0) : Rational(1);
  if (c.L(2) == 0) c.L(2) = Rational(7, 3);
  c.x = rng.vec4();
  c.x(3) = Rational(1);
  // Adjust A33 and A03 (symmetric) so that x^T A x = 0 and x^T A L = 0:
  //  x^T A x + a (x3^2) + b (2 x0 x3) = 0,  x^T A L + a (x3 L3) + b (x0 L3 + x3 L0) = 0.
  const Rational f1 = c.x.dot(c.A * c.x), f2 = c.x.dot(c.A * c.L);
  const Rational a11 = c.x(3) * c.x(3), a12 = 2 * c.x(0) * c.x(3);
  const Rational a21 = c.x(3) * c.L(3), a22 = c.x(0) * c.L(3) + c.x(3) * c.L(0);
  const Rational det = a11 * a22 - a12 * a21;
  if (det != 0) {
    const Rational a = (-f1 * a22 + f2 * a12) / det, b = (-a11 * f2 + a21 * f1) / det;
    c.A(3, 3) += a;
    c.A(0, 3) += b;
    c.A(3, 0) += b;
  } else {  // only x^T A x = 0 is needed for the reflection laws
    c.A(3, 3) -= f1 / a11;
    c.on_terminator = false;
  }
  c.plane = rng.vec4();
  if (c.plane(0) == 0 && c.plane(1) == 0 && c.plane(2) == 0) c.plane(2) = 1;
  // a point of the plane: move a random point along n onto it
  Vec4<Rational> y = rng.vec4();
  y(3) = 1;
  const Vec3<Rational> n = c.plane.head<3>();
  const Rational t = -(n.dot(y.head<3>()) + c.plane(3)) / n.squaredNorm();
  c.on_plane = y;
  c.on_plane.head<3>() += t * n;
  return c;
}

/// Runs every law on a case in scalar type S.
template <class S> void run_laws(const ExactCase& c) {
  const Mat4<S> A = to_scalar<S>(c.A);
  const Vec4<S> L = to_scalar<S>(c.L), x = to_scalar<S>(c.x), plane = to_scalar<S>(c.plane),
                on_plane = to_scalar<S>(c.on_plane);
  for (Method m : {Method::direct, Method::paper}) {
    law_symmetry<S>(A, L, plane, m);
    law_reflection_incidence<S>(A, plane, x, m);
    if (c.on_terminator) law_terminator<S>(A, L, x, m);
  }
  law_mirror_involution<S>(plane, on_plane);
  law_routes_agree<S>(A, L, plane);
}

/// Special and near-degenerate inputs built from shapes with integer data
/// (exactly representable in every type): cylinders, cones, an almost-cone.
template <class S> void run_special_laws() {
  const Vec3<S> p(S(1), S(-2), S(3)), axis(S(0), S(1), S(1));
  const std::vector<Mat4<S>> shapes = {
      cylinder_quadric<S>(p, axis, S(1) / S(2)),
      cone_quadric<S>(p, Vec3<S>(S(0), S(0), S(1)), S(1) / S(3)),
      // near-degenerate: ellipsoid with radii 1, 1, 2^20 (almost a cylinder)
      ellipsoid_quadric<S>(p, Vec3<S>(S(1), S(1), S(1 << 20)), Mat3<S>::Identity()),
      sphere_quadric<S>(Vec3<S>(S(0), S(0), S(2)), S(1)),
  };
  const std::vector<Vec4<S>> lights = {Vec4<S>(S(3), S(4), S(8), S(1)), Vec4<S>(S(1), S(-2), S(-4), S(0)),
                                       Vec4<S>(S(0), S(0), S(9), S(1))};
  const Vec4<S> plane(S(1), S(2), S(2), S(-5));
  for (const auto& A : shapes)
    for (const auto& L : lights) {
      law_symmetry<S>(A, L, plane, Method::direct);
      law_symmetry<S>(A, L, plane, Method::paper);
      law_routes_agree<S>(A, L, plane);
    }
}

/// The whole law suite for S: random point and parallel lights, special shapes.
template <class S> void run_law_suite(int cases) {
  RandomRationals rng(20261121);
  for (int i = 0; i < cases; ++i) {
    const ExactCase c = random_case(rng, i % 3 == 0);
    run_laws<S>(c);
  }
  run_special_laws<S>();
}

}  // namespace qverify::test
