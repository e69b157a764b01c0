// Analytic cases with known answers, in exact arithmetic (identities) and in double.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>
#include <qverify/exact/statuses.hpp>

#include <cmath>

using namespace qverify;
using Q = Rational;

namespace {
Mat4<Q> unit_sphere() { return sphere_quadric<Q>(Vec3<Q>::Zero(), Q(1)); }
Vec4<Q> point(const Q& x, const Q& y, const Q& z) { return Vec4<Q>(x, y, z, Q(1)); }
}  // namespace

TEST_CASE("unit sphere lit from (0 0 d): cone half-angle asin(1/d) - terminator plane z = 1/d", "[analytic][exact]") {
  const Q d(5, 3);  // sin(half angle) = 3/5, cos = 4/5: every point below is rational
  const Vec4<Q> L = point(0, 0, d);
  for (Method m : {Method::direct, Method::paper}) {
    const auto sh = shadow<Q>(unit_sphere(), L, m);
    REQUIRE(std::string(sh.status()) == "ok");
    // terminator plane: z = 1/d, i.e. (0, 0, 1, -1/d) up to a positive factor
    CHECK(proportional(sh.polar_plane, Vec4<Q>(0, 0, 1, -Q(3, 5)), Factor::positive, Q(0)));
    // generators of the cone: apex + t (sin cos phi, sin sin phi, -cos), cos phi = 3/5, sin phi = 4/5
    for (const Q& t : {Q(1), Q(7, 2), Q(-2)}) {
      const Vec4<Q> x = point(t * Q(3, 5) * Q(3, 5), t * Q(3, 5) * Q(4, 5), d - t * Q(4, 5));
      CHECK(x.dot(sh.P * x) == 0);
    }
    // a ray at another angle is not on the cone
    const Vec4<Q> off = point(Q(1, 2), 0, d - 1);
    CHECK(off.dot(sh.P * off) != 0);
    // the terminator circle z = 3/5, x^2 + y^2 = 16/25 lies on A, P and R
    const Vec4<Q> c = point(Q(4, 5) * Q(3, 5), Q(4, 5) * Q(4, 5), Q(3, 5));
    CHECK(c.dot(unit_sphere() * c) == 0);
    CHECK(c.dot(sh.P * c) == 0);
    CHECK(c.dot(sh.R * c) == 0);
  }
}

TEST_CASE("unit sphere lit from (0 0 2) in double: half-angle 30 degrees", "[analytic][double]") {
  const Mat4<double> A = sphere_quadric<double>(Vec3<double>::Zero(), 1.0);
  const Vec4<double> L(0, 0, 2, 1);
  const double half = std::asin(1.0 / 2.0);
  for (Method m : {Method::direct, Method::paper}) {
    const auto sh = shadow<double>(A, L, m);
    for (double phi : {0.0, 1.0, 2.5}) {
      const Vec3<double> dir(std::sin(half) * std::cos(phi), std::sin(half) * std::sin(phi), -std::cos(half));
      const Vec4<double> x(3 * dir(0), 3 * dir(1), 2 + 3 * dir(2), 1);
      CHECK(test::incidence<double>(sh.P, x) < 1e-14);
    }
    CHECK(proportional(sh.polar_plane, Vec4<double>(0, 0, 1, -0.5), Factor::positive, 1e-15));
  }
}

TEST_CASE("parallel light along -z: the tangent cone is the cylinder x^2 + y^2 = 1", "[analytic][exact]") {
  const Vec4<Q> L(0, 0, 1, 0);  // direction (0, 0, -1): light at infinity above
  for (Method m : {Method::direct, Method::paper}) {
    const auto sh = shadow<Q>(unit_sphere(), L, m);
    Mat4<Q> cyl = Mat4<Q>::Zero();
    cyl(0, 0) = cyl(1, 1) = 1;
    cyl(3, 3) = -1;
    CHECK(proportional(sh.P, cyl, Factor::positive, Q(0)));
    CHECK(proportional(sh.polar_plane, Vec4<Q>(0, 0, 1, 0), Factor::positive, Q(0)));
  }
}

TEST_CASE("mirror image of a sphere is the sphere about the reflected centre", "[analytic][exact]") {
  const Vec3<Q> c(1, -2, 3);
  const Mat4<Q> A = sphere_quadric<Q>(c, Q(3, 2));
  const Vec4<Q> plane(Q(1, 3), Q(2, 3), Q(2, 3), -5);  // the scene's "slant" mirror, |n| = 1
  const Vec4<Q> plane2(1, 2, 2, -15);                 // the same plane, non-unit normal
  const Mat4<Q> M = mirror_matrix<Q>(plane);
  CHECK(M == mirror_matrix<Q>(plane2));
  const Vec4<Q> c4(c(0), c(1), c(2), 1);
  const Vec4<Q> mc = M * c4;
  const Mat4<Q> expected = sphere_quadric<Q>(mc.head<3>(), Q(3, 2));
  for (Method m : {Method::direct, Method::paper}) {
    CHECK(reflection<Q>(A, M, m).B == expected);
    CHECK(reflection_in_plane<Q>(A, plane, m).B == expected);
    CHECK(reflection_in_plane<Q>(A, plane2, m).B == expected);  // any scale of the plane
  }
  CHECK((M * M).isIdentity(Q(0)));
}

TEST_CASE("mirror matrix: involution and fixed plane - double", "[analytic][double]") {
  const Vec4<double> plane(1, 1, 0, -10);
  const Mat4<double> M = mirror_matrix<double>(plane);
  CHECK((M * M - Mat4<double>::Identity()).cwiseAbs().maxCoeff() < 1e-15);
  const Vec4<double> on(10, 0, 3, 1), off(0, 0, 0, 1);
  CHECK((M * on - on).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((M * off - Vec4<double>(10, 10, 0, 1)).cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("status words of the special cases", "[analytic][status]") {
  const Mat4<Q> A = unit_sphere();
  SECTION("light inside: no real silhouette") {
    CHECK(std::string(shadow<Q>(A, point(0, Q(1, 2), 0), Method::direct).status()) == "no-real-silhouette");
  }
  SECTION("light on the surface") {
    CHECK(std::string(shadow<Q>(A, point(Q(3, 5), Q(4, 5), 0), Method::direct).status()) == "light-on-surface");
    // In double, statuses are predicates of the doubles' exact values: 0.6 and 0.8 are not exactly on the
    // sphere (the filter cannot tell, the exact settlement says ok), (0.5, 0.75, sqrt(3)/4 rounded) neither;
    // (1, 0, 0) is, and 1 + 2^-52 is not.
    const Mat4<double> A1 = sphere_quadric<double>(Vec3<double>::Zero(), 1.0);
    auto settled = [&](const Vec4<double>& L) {
      auto sh = shadow<double>(A1, L, Method::direct);
      settle_status(sh, A1, L);
      return std::string(sh.status());
    };
    CHECK(std::string(shadow<double>(A1, Vec4<double>(0.6, 0.8, 0, 1), Method::direct).status()) == "undecided");
    CHECK(settled(Vec4<double>(0.6, 0.8, 0, 1)) == "ok");
    CHECK(settled(Vec4<double>(1, 0, 0, 1)) == "light-on-surface");
    CHECK(settled(Vec4<double>(0.5, std::sqrt(0.75), 0, 1)) != "light-on-surface");
    CHECK(settled(Vec4<double>(1 + 0x1p-52, 0, 0, 1)) == "ok");
    CHECK(settled(Vec4<double>(1 - 0x1p-53, 0, 0, 1)) == "no-real-silhouette");
  }
  SECTION("no real point at all") {
    Mat4<Q> imaginary = Mat4<Q>::Identity();  // x^2 + y^2 + z^2 + 1 = 0
    CHECK(std::string(shadow<Q>(imaginary, point(5, 0, 0), Method::direct).status()) == "no-real-silhouette");
  }
  SECTION("degenerate quadric: a plane pair") {
    const Mat4<Q> pair = plane_pair<Q>(Vec4<Q>(1, 0, 0, 0), Vec4<Q>(0, 1, 0, -1));
    CHECK(std::string(shadow<Q>(pair, point(3, 4, 5), Method::direct).status()) == "degenerate-quadric");
    CHECK(std::string(reflection<Q>(pair, mirror_matrix<Q>(Vec4<Q>(0, 0, 1, 0)), Method::direct).status()) ==
          "degenerate-quadric");
  }
  SECTION("cylinders and cones are proper shapes") {
    const Mat4<Q> cyl = cylinder_quadric<Q>(Vec3<Q>::Zero(), Vec3<Q>(0, 1, 1), Q(1, 2));
    CHECK(std::string(shadow<Q>(cyl, point(Q(1, 10), Q(1, 5), Q(97, 10)), Method::direct).status()) == "ok");
  }
  SECTION("paper route: singular frame for l_z = 0 and horizontal parallel light; direct fallback") {
    const auto sh = shadow<Q>(A, point(3, 4, 0), Method::paper);
    CHECK(std::string(sh.status()) == "singular-frame");
    CHECK(sh.direct_fallback);
    CHECK(sh.P == tangent_cone<Q>(A, point(3, 4, 0)));
    CHECK(std::string(shadow<Q>(A, point(3, 4, 0), Method::direct).status()) == "ok");
    CHECK(std::string(shadow<Q>(A, Vec4<Q>(1, 2, 0, 0), Method::paper).status()) == "singular-frame");
  }
  SECTION("paper route for a light below the xy plane keeps the orientation") {
    const Vec4<Q> L = point(1, 2, -3);
    const auto p = shadow<Q>(A, L, Method::paper), d = shadow<Q>(A, L, Method::direct);
    CHECK(proportional(p.polar_plane, d.polar_plane, Factor::positive, Q(0)));
    CHECK(proportional(p.P, d.P, Factor::positive, Q(0)));
  }
}

TEST_CASE("shapes: matrices built without square roots", "[analytic][shapes]") {
  const Vec3<Q> c(1, 2, 3);
  SECTION("ellipsoid with identity axes and equal radii is the sphere (times det^2)") {
    const Mat4<Q> E = ellipsoid_quadric<Q>(c, Vec3<Q>(2, 2, 2), Mat3<Q>::Identity());
    CHECK(proportional(E, sphere_quadric<Q>(c, Q(2)), Factor::positive, Q(0)));
  }
  SECTION("rotated ellipsoid contains the images of unit vectors") {
    Mat3<Q> R;
    R << Q(3, 5), Q(-4, 5), 0, Q(4, 5), Q(3, 5), 0, 0, 0, 1;
    const Vec3<Q> radii(1, 2, Q(3, 4));
    const Mat4<Q> E = ellipsoid_quadric<Q>(c, radii, R);
    for (int k = 0; k < 3; ++k) {
      const Vec3<Q> p = c + R * radii.asDiagonal() * Vec3<Q>::Unit(k);
      const Vec4<Q> x(p(0), p(1), p(2), 1);
      CHECK(x.dot(E * x) == 0);
    }
    const Vec4<Q> centre(c(0), c(1), c(2), 1);
    CHECK(centre.dot(E * centre) < 0);  // negative inside
  }
  SECTION("cylinder and cone: points at the right distance, negative inside") {
    const Vec3<Q> axis(0, 0, 2);
    const Mat4<Q> cyl = cylinder_quadric<Q>(c, axis, Q(1, 2));
    CHECK(Vec4<Q>(Q(3, 2), 2, 100, 1).dot(cyl * Vec4<Q>(Q(3, 2), 2, 100, 1)) == 0);
    CHECK(Vec4<Q>(1, 2, 0, 1).dot(cyl * Vec4<Q>(1, 2, 0, 1)) < 0);
    const Mat4<Q> cone = cone_quadric<Q>(c, axis, Q(1, 3));
    const Vec4<Q> g(1 + Q(1, 3) * 6, 2, 3 + 6, 1);  // 6 up the axis, 2 out
    CHECK(g.dot(cone * g) == 0);
    CHECK(Vec4<Q>(1, 2, 5, 1).dot(cone * Vec4<Q>(1, 2, 5, 1)) < 0);
  }
  SECTION("coefficients: off-diagonal entries are half the mixed coefficients") {
    const Mat4<Q> A = quadric_from_coefficients<Q>(1, -1, 0, 2, 0, 0, 0, 0, -2, Q(1, 10));
    CHECK(A(0, 1) == 1);
    CHECK(A(2, 3) == -1);
    CHECK(A(3, 3) == Q(1, 10));
  }
}

namespace {
/// V^T D V for an integer V with |det V| > 0: by Sylvester's law of inertia it has D's signs.
template <int k> Eigen::Matrix<Q, k, k> congruent_form(std::mt19937_64& g, const std::array<int, k>& signs) {
  std::uniform_int_distribution<int> entry(-6, 6), size(1, 9);
  Eigen::Matrix<Q, k, k> V, D = Eigen::Matrix<Q, k, k>::Zero();
  do {
    for (Eigen::Index i = 0; i < V.size(); ++i) V(i) = Q(entry(g));
  } while (Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic>(V).determinant() == 0);
  for (int i = 0; i < k; ++i) D(i, i) = Q(signs[static_cast<std::size_t>(i)] * size(g), size(g));
  return V.transpose() * D * V;
}

template <int k> void check_definiteness(std::mt19937_64& g) {
  for (int trial = 0; trial < 200; ++trial) {
    std::array<int, k> signs{};
    std::uniform_int_distribution<int> sign(-1, 1), mode(0, 2);
    const int m = mode(g);  // all positive, all negative, or mixed (zeros included)
    for (int& s : signs) s = m == 0 ? 1 : m == 1 ? -1 : sign(g);
    const int expected = m == 0 ? 1 : m == 1 ? -1
                         : std::all_of(signs.begin(), signs.end(), [](int s) { return s > 0; })  ? 1
                         : std::all_of(signs.begin(), signs.end(), [](int s) { return s < 0; }) ? -1
                                                                                                  : 0;
    const Eigen::Matrix<Q, k, k> M = congruent_form<k>(g, signs);
    INFO("k = " << k << ", signs " << signs[0] << " ..., M =\n" << M);
    CHECK(definiteness<Q, k>(M) == std::optional<int>(expected));
    // a rounding scalar behind its filter: the exact answer or none, never another
    using F = PredicateScalar<double>;
    Eigen::Matrix<double, k, k> Md;
    for (Eigen::Index i = 0; i < M.size(); ++i) Md(i) = M(i).template convert_to<double>();
    const bool representable = Eigen::Matrix<Q, k, k>(Md.template cast<Q>()) == M;
    const auto filtered = definiteness<F, k>(to_predicate<F>(Md));
    if (representable) CHECK((!filtered || *filtered == expected));
  }
}
}  // namespace

TEST_CASE("definiteness: Sylvester's test gives the inertia's answer, for 2, 3 and 4 variables", "[analytic][status]") {
  // The one definiteness test (core/predicates.hpp): the no-real-silhouette predicate's conic, the
  // sampler's sections and quadrics without real points, eval's ellipsoids. Forms V^T D V, D of known
  // signs (Sylvester's law of inertia), exact; a double's filter answers the same or not at all.
  std::mt19937_64 g(20261204);
  check_definiteness<2>(g);
  check_definiteness<3>(g);
  check_definiteness<4>(g);
  // a zero leading entry: neither, though the rest is definite on its own
  Mat3<Q> K = Mat3<Q>::Identity();
  K(0, 0) = 0;
  CHECK(definiteness<Q, 3>(K) == std::optional<int>(0));
  CHECK(conic_definite<Q>(Mat3<Q>(-Mat3<Q>::Identity())) == Truth::yes);
  CHECK(conic_definite<Q>(Mat3<Q>(Vec3<Q>(1, 1, -1).asDiagonal())) == Truth::no);
}
