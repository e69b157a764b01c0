// The filtered point check (verify/point_filter.hpp) against the verifier's exact
// measure. Speed is not tested here: `qverify bench` measures it.
#include <qverify/core/core.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/wide_int.hpp>
#include <qverify/verify/point_filter.hpp>

#include "laws.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace qverify;
using qverify::test::pow10;
using qverify::test::pow2;
using qverify::test::random_double;

namespace {

using Q = Rational;

struct Item {
  Mat4<Q> A;
  Vec4<Q> L;
};
Item random_item(std::mt19937_64& g, int spread = 30) {
  Item it;
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) it.A(i, j) = it.A(j, i) = Q(random_double(g, spread));
  for (int i = 0; i < 3; ++i) it.L(i) = Q(random_double(g, spread));
  it.L(3) = 1;
  return it;
}

Mat4<double> rounded(const Mat4<Q>& m) {
  Mat4<double> out;
  RoundingReport rep;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = round_rational<double>(m(i), rep);
  return out;
}
Vec4<double> rounded(const Vec4<Q>& v) {
  Vec4<double> out;
  RoundingReport rep;
  for (int i = 0; i < 4; ++i) out(i) = round_rational<double>(v(i), rep);
  return out;
}
template <int R, int C> Eigen::Matrix<Q, R, C> exactly(const Eigen::Matrix<double, R, C>& m) {
  return m.unaryExpr([](double v) { return Q(v); });
}

/// The exact relative error of one point (the verifier's measure), and the decision at T.
Measure point_error(const RootPoint& x, const Mat4<Q>& Qm, const Measure& size) {
  return relative(measure_quadric({x}, Qm), size);
}
Measure point_error(const RootPoint& x, const Vec4<Q>& pi, const Measure& size) {
  return relative(measure_plane({x}, pi), size);
}

struct Tally {
  long stage1 = 0, stage2 = 0, stage3 = 0;
};

/// For every point: the filter's decision (where it decides) and the exact integers'
/// (where they decide) equal the exact one; the whole check's per-point verdicts too.
template <class Candidate>
void compare_at(const FilterPoints& pts, const Candidate& c, const std::vector<Measure>& errors, Tally& tally) {
  const auto exact_c = exactly(c);
  std::vector<char> passed;
  FilterCounts counts;
  if constexpr (Candidate::ColsAtCompileTime == 4) counts = check_quadric_filtered(pts, c, &passed);
  else counts = check_plane_filtered(pts, c, &passed);
  REQUIRE(passed.size() == pts.exact.size());
  std::size_t failed = 0;
  for (std::size_t k = 0; k < pts.exact.size(); ++k) {
    const bool exact_pass = !(errors[k] > pts.target.T);
    INFO("point " << k << ", exact error " << static_cast<double>(errors[k]) << ", T " << pts.target.accuracy);
    // the verifier's own decision, as point_filter exposes it
    if constexpr (Candidate::ColsAtCompileTime == 4) CHECK(exact_quadric_passes(pts.exact[k], exact_c, pts.target) == exact_pass);
    else CHECK(exact_plane_passes(pts.exact[k], exact_c, pts.target) == exact_pass);
    FilterVerdict v1, v2;
    if constexpr (Candidate::ColsAtCompileTime == 4) {
      v1 = filter_quadric_guarded(pts.enclosed[k], c, pts.target);
      v2 = pts.cleared.decide_quadric(k, IntegerQuadric(c), pts.target);
    } else {
      v1 = filter_plane_guarded(pts.enclosed[k], c, pts.target);
      v2 = pts.cleared.decide_plane(k, IntegerPlane(c), pts.target);
    }
    if (v1 != FilterVerdict::undecided) {
      ++tally.stage1;
      CHECK((v1 == FilterVerdict::pass) == exact_pass);
    } else if (v2 != FilterVerdict::undecided) {
      ++tally.stage2;
    } else {
      ++tally.stage3;
    }
    if (v2 != FilterVerdict::undecided) CHECK((v2 == FilterVerdict::pass) == exact_pass);
    CHECK((passed[k] != 0) == exact_pass);
    failed += exact_pass ? 0 : 1;
  }
  CHECK(counts.checked == pts.exact.size());
  CHECK(counts.failed == failed);
  CHECK(counts.measured <= counts.fallbacks);
}

/// Targets around the exact errors: the worst point's error times (1 +- 1e-6), a
/// middle point's error times (1 +- 1e-12), and a point's error rounded to double
/// (the boundary itself, to 17 digits).
std::vector<double> boundary_targets(std::vector<Measure> errors) {
  std::vector<double> ts{kDefaultAccuracy};
  std::vector<Measure> finite;
  for (const Measure& e : errors)
    if (e > 0 && e < std::numeric_limits<Measure>::infinity()) finite.push_back(e);
  if (finite.empty()) return ts;
  std::sort(finite.begin(), finite.end());
  const double worst = static_cast<double>(finite.back()), mid = static_cast<double>(finite[finite.size() / 2]);
  for (double f : {1 + 1e-6, 1 - 1e-6}) ts.push_back(worst * f);
  for (double f : {1 + 1e-12, 1 - 1e-12}) ts.push_back(mid * f);
  ts.push_back(mid);
  return ts;
}

template <class Candidate>
void compare_around(const std::vector<RootPoint>& pts, const Measure& size, const Candidate& c, Tally& tally,
                    std::vector<double> extra = {}) {
  std::vector<Measure> errors;
  for (const RootPoint& x : pts) errors.push_back(point_error(x, exactly(c), size));
  std::vector<double> ts = boundary_targets(errors);
  ts.insert(ts.end(), extra.begin(), extra.end());
  for (double T : ts) {
    INFO("T = " << T);
    compare_at(FilterPoints(pts, size, T), c, errors, tally);
  }
}

/// P + t e4 e4^T, rounded: the perturbation adds t w^2 to x^T P x and leaves the
/// gradient's x, y, z alone, so at a point of the exact P its distance is
/// |t| |w| / (2 |(P x)_xyz|). t is chosen so that the worst point's error is about T.
Mat4<double> perturbed_cone(const Mat4<Q>& P, const std::vector<RootPoint>& pts, const Measure& size, double T, double f) {
  Measure worst = 0;
  for (const RootPoint& x : pts) {
    const auto c = x.coords();
    Measure g = 0;
    for (int i = 0; i < 3; ++i) {
      const Measure gi = to_measure(x.linear(P.row(i).transpose()));
      g += gi * gi;
    }
    if (g == 0) continue;
    const Measure h = abs(to_measure(c[3])) / (2 * sqrt(g));
    if (h > worst) worst = h;
  }
  Mat4<Q> Pp = P;
  if (worst > 0) Pp(3, 3) += Q(static_cast<double>(Measure(T * f * size / worst)));
  return rounded(Pp);
}

}  // namespace

TEST_CASE("filter: decisions equal the exact measure on terminator points of double-valued items", "[filter]") {
  std::mt19937_64 g(7);
  Tally tally;
  int items = 0;
  for (int k = 0; k < 6 && items < 3; ++k) {
    const Item it = random_item(g);
    const ItemPoints ip = terminator_points(it.A, it.L, 24, item_seed(1, 1, it.A, it.L));
    if (ip.points.empty()) continue;
    ++items;
    INFO("item " << k);
    const Vec4<Q> pi = polar_plane<Q>(it.A, it.L);
    const Mat4<Q> P = tangent_cone_from_polar<Q>(it.A, it.L, pi), R = terminator_quadric_from_polar<Q>(it.L, pi);
    // the correctly rounded results
    compare_around(ip.points, ip.size, rounded(P), tally);
    compare_around(ip.points, ip.size, rounded(R), tally);
    compare_around(ip.points, ip.size, rounded(pi), tally);
    // candidates perturbed so that their error is about T (1 +- 1e-6), judged at T
    for (double f : {1 + 1e-6, 1 - 1e-6}) {
      const Mat4<double> Pp = perturbed_cone(P, ip.points, ip.size, kDefaultAccuracy, f);
      compare_around(ip.points, ip.size, Pp, tally, {kDefaultAccuracy});
    }
  }
  CHECK(items == 3);
  CHECK(tally.stage1 > 0);
  INFO("decided by the filter " << tally.stage1 << ", by exact integers " << tally.stage2 << ", by the measure " << tally.stage3);
  CHECK(tally.stage2 + tally.stage3 > 0);  // the boundary targets reach past the filter
}

TEST_CASE("filter: decisions equal the exact measure on reflected points", "[filter]") {
  std::mt19937_64 g(8);
  Tally tally;
  for (int k = 0; k < 3; ++k) {
    const Item it = random_item(g);
    const ItemPoints ip = reflected_points(it.A, reference_mirror(it.L), 24, item_seed(1, 2, it.A, it.L));
    if (ip.points.empty()) continue;
    INFO("item " << k);
    const Mat4<Q> B = mirror_image_of_plane<Q>(it.A, it.L);
    compare_around(ip.points, ip.size, rounded(B), tally);
    Mat4<Q> Bp = B;
    Bp(0, 0) *= Q(1) + Q(1) / Q(1 << 20);  // far from exact: certainly beyond T somewhere
    compare_around(ip.points, ip.size, rounded(Bp), tally);
  }
  CHECK(tally.stage1 > 0);
}

TEST_CASE("filter: huge radicands, far points, tiny and huge coordinates", "[filter]") {
  std::mt19937_64 g(9);
  Tally tally;
  using boost::multiprecision::mpz_int;
  for (int k = 0; k < 12; ++k) {
    // x = p + sqrt(d) q with d about 2^(400 k) and q about 2^(-200 k): sqrt(d) q of order 1
    const int e = 200 * (k % 6);
    const mpz_int big = (mpz_int(1) << (2 * e)) + mpz_int(g() % 1000 + 1);
    const Q d = Q(big);
    const Q scale = k < 6 ? Q(1) : Q(mpz_int(1) << 300);  // far away too (coordinates 2^300)
    Vec4<Q> p, q;
    for (int i = 0; i < 3; ++i) {
      p(i) = scale * Q(static_cast<long>(g() % 2001) - 1000) / Q(static_cast<long>(g() % 97) + 1);
      q(i) = Q(static_cast<long>(g() % 2001) - 1000) / Q(mpz_int(1) << e) / Q(static_cast<long>(g() % 13) + 1);
    }
    p(3) = 1, q(3) = 0;
    std::vector<RootPoint> pts;
    pts.emplace_back(p, q, d);
    pts.emplace_back(p, Vec4<Q>(-q), d);
    // the enclosure contains the coordinates (to 80 digits)
    for (const RootPoint& x : pts) {
      const EnclosedPoint enc = enclose_point(x);
      const auto c = x.coords();
      for (int i = 0; i < 4; ++i) {
        const Measure v = to_measure(c[static_cast<std::size_t>(i)]);
        CHECK(Measure(enc.x[static_cast<std::size_t>(i)].inf()) <= v);
        CHECK(v <= Measure(enc.x[static_cast<std::size_t>(i)].sup()));
      }
    }
    // a random double sphere-ish quadric through about that region, and sizes of every kind
    Mat4<double> Qd = Mat4<double>::Zero();
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) Qd(i, j) = Qd(j, i) = random_double(g, 8);
    for (double size : {1.0, 1e-8, 1e8}) compare_around(pts, Measure(size), Qd, tally, {1e-3, 1.0, 1e3});
    compare_around(pts, Measure(1), Vec4<double>(random_double(g, 4), random_double(g, 4), random_double(g, 4), 1.0), tally);
  }
  CHECK(tally.stage1 > 0);
}

TEST_CASE("filter: far frames, world and local", "[filter]") {
  // a sphere of radius 3 centred 1e7 away, lit from nearby; the world-frame result carries the
  // rounding of a far frame (large errors), the local one does not
  Tally tally;
  const Vec3<Q> c(Q(10000019), Q(-20000003), Q(30000001));
  Mat4<Q> A = Mat4<Q>::Identity();
  A(3, 3) = c.squaredNorm() - 9;
  for (int i = 0; i < 3; ++i) A(i, 3) = A(3, i) = -c(i);
  const Vec4<Q> L(c(0) + 5, c(1) + Q(7) / 2, c(2) - 4, Q(1));
  const ItemPoints ip = terminator_points(A, L, 32, 5);
  REQUIRE(!ip.points.empty());
  const Mat4<Q> P = tangent_cone<Q>(A, L);
  compare_around(ip.points, ip.size, rounded(P), tally);
  // local frame: points moved exactly to the centre, the cone computed there
  const Mat4<Q> Tr = translation<Q>(c);
  const Mat4<Q> A_local = Tr.transpose() * A * Tr;
  Vec4<Q> L_local = L;
  L_local.head<3>() -= c;
  const std::vector<RootPoint> local = in_frame(ip.points, c);
  compare_around(local, ip.size, rounded(Mat4<Q>(tangent_cone<Q>(A_local, L_local))), tally);
  CHECK(tally.stage1 > 0);
}

TEST_CASE("filter: a terminator that is a single point (the relative residual rule)", "[filter]") {
  // the cone x^2 + y^2 = z^2 lit along its axis: the terminator is the apex
  Mat4<Q> A = Mat4<Q>::Zero();
  A(0, 0) = A(1, 1) = 1, A(2, 2) = -1;
  const Vec4<Q> L(0, 0, 1, 1);
  const ItemPoints ip = terminator_points(A, L, 8, 3);
  REQUIRE(!ip.points.empty());
  REQUIRE(!(ip.size > 0));
  const Mat4<Q> P = tangent_cone<Q>(A, L);
  Tally tally;
  compare_around(ip.points, ip.size, rounded(P), tally);
  for (double t : {1e-3, 1e-12, 3e-9}) {
    Mat4<Q> Pp = P;
    Pp(3, 3) += Q(t);
    compare_around(ip.points, ip.size, rounded(Pp), tally, {kDefaultAccuracy, t, t * (1 + 1e-9)});
  }
  FilterPoints fp(ip.points, ip.size, kDefaultAccuracy);
  CHECK(fp.target.residual_rule);
}

TEST_CASE("filter: points exactly on the candidate, at its singular point, at infinity", "[filter]") {
  Mat4<double> S = Mat4<double>::Identity();
  S(3, 3) = -1;  // the unit sphere
  std::vector<RootPoint> pts;
  pts.emplace_back(Vec4<Q>(1, 0, 0, 1), Vec4<Q>::Zero(), Q(0));                              // on it: f = 0
  pts.emplace_back(Vec4<Q>(Q(3) / 5, Q(4) / 5, 0, 1), Vec4<Q>::Zero(), Q(0));                // on it, rational
  pts.emplace_back(Vec4<Q>(0, 0, 0, 1), Vec4<Q>::Zero(), Q(0));                              // the centre: gradient 0
  pts.emplace_back(Vec4<Q>(1, 0, 0, 0), Vec4<Q>::Zero(), Q(0));                              // w = 0
  pts.emplace_back(Vec4<Q>(0, Q(1) / 2, 0, 1), Vec4<Q>(1, 0, 0, 0), Q(3) / 4);               // (sqrt(3)/2, 1/2, 0): on it
  pts.emplace_back(Vec4<Q>(0, Q(1) / 2, 0, 1), Vec4<Q>(1, 0, 0, 0), Q(3) / 4 + Q(1) / 1024);  // just off it
  Tally tally;
  compare_around(pts, Measure(1), S, tally, {1e-30, 1e-3, 1.0});
  FilterPoints fp(pts, Measure(1), kDefaultAccuracy);
  std::vector<char> passed;
  const FilterCounts n = check_quadric_filtered(fp, S, &passed);
  CHECK(passed == std::vector<char>{1, 1, 0, 0, 1, 0});
  CHECK(n.failed == 3);
}

TEST_CASE("filter: the proof mode on cleared integers equals RootPoint::form", "[filter]") {
  std::mt19937_64 g(10);
  for (int k = 0; k < 3; ++k) {
    const Item it = random_item(g);
    const ItemPoints ip = terminator_points(it.A, it.L, 16, item_seed(2, 1, it.A, it.L));
    if (ip.points.empty()) continue;
    const ClearedPoints cp(ip.points);
    const Vec4<Q> pi = polar_plane<Q>(it.A, it.L);
    const Mat4<Q> P = tangent_cone_from_polar<Q>(it.A, it.L, pi);
    Mat4<Q> Pbad = P;
    Pbad(1, 2) += 1, Pbad(2, 1) += 1;
    Vec4<Q> pibad = pi;
    pibad(3) += Q(1) / 3;
    for (std::size_t j = 0; j < ip.points.size(); ++j) {
      CHECK(cp.on_quadric(j, IntegerQuadric(P)) == CGAL::is_zero(ip.points[j].form(P)));
      CHECK(cp.on_quadric(j, IntegerQuadric(Pbad)) == CGAL::is_zero(ip.points[j].form(Pbad)));
      CHECK(cp.on_plane(j, IntegerPlane(pi)) == CGAL::is_zero(ip.points[j].linear(pi)));
      CHECK(cp.on_plane(j, IntegerPlane(pibad)) == CGAL::is_zero(ip.points[j].linear(pibad)));
    }
    CHECK(cp.check_quadric(IntegerQuadric(P)).failed == 0);
    CHECK(cp.check_plane(IntegerPlane(pi)).failed == 0);
  }
  // square radicands (x rational in disguise), rational points, d = 0
  Mat4<Q> S = Mat4<Q>::Identity();
  S(3, 3) = -25;  // radius 5
  std::vector<RootPoint> pts;
  pts.emplace_back(Vec4<Q>(0, 4, 0, 1), Vec4<Q>(1, 0, 0, 0), Q(9));      // (3, 4, 0): on it
  pts.emplace_back(Vec4<Q>(0, 4, 0, 1), Vec4<Q>(-1, 0, 0, 0), Q(9));     // (-3, 4, 0): on it
  pts.emplace_back(Vec4<Q>(0, 4, 0, 1), Vec4<Q>(1, 0, 0, 0), Q(16));     // (4, 4, 0): off
  pts.emplace_back(Vec4<Q>(5, 0, 0, 1), Vec4<Q>::Zero(), Q(0));           // rational, on
  pts.emplace_back(Vec4<Q>(5, 0, 0, 1), Vec4<Q>(1, 1, 1, 0), Q(0));       // d = 0, on
  pts.emplace_back(Vec4<Q>(0, 0, 0, 1), Vec4<Q>(1, 0, 0, 0), Q(25) / 4);  // (5/2, 0, 0): off
  const ClearedPoints cp(pts);
  const Vec4<Q> plane(1, 0, 0, -3);
  for (std::size_t j = 0; j < pts.size(); ++j) {
    INFO("point " << j);
    CHECK(cp.on_quadric(j, IntegerQuadric(S)) == CGAL::is_zero(pts[j].form(S)));
    CHECK(cp.on_plane(j, IntegerPlane(plane)) == CGAL::is_zero(pts[j].linear(plane)));
  }
  CHECK(cp.check_quadric(IntegerQuadric(S)).failed == 2);
}
