// The filtered point check (verify/point_filter.hpp) against the verifier's exact
// measure, and the exact arithmetic for doubles and decimal text (exact/wide_int.hpp,
// core/mirror_division_free.hpp) against GMP rationals. Speed is not tested here:
// `qverify bench` measures it.
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

namespace {

using Q = Rational;

/// A double with a full mantissa and |x| in [2^e, 2^(e+1)), e uniform in [-spread, spread].
double random_double(std::mt19937_64& g, int spread = 30) {
  const std::uint64_t m = (g() >> 11) | (std::uint64_t(1) << 52);
  const int e = static_cast<int>(g() % static_cast<std::uint64_t>(2 * spread + 1)) - spread;
  const double x = std::ldexp(static_cast<double>(m), e - 52);
  return (g() & 1) ? -x : x;
}

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
    const ItemPoints ip = terminator_points(it.A, it.L, 24, item_seed(1, 1, static_cast<std::size_t>(k)));
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
    const ItemPoints ip = reflected_points(it.A, reference_mirror(it.L), 24, item_seed(1, 2, static_cast<std::size_t>(k)));
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
    const ItemPoints ip = terminator_points(it.A, it.L, 16, item_seed(2, 1, static_cast<std::size_t>(k)));
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

// ------------------------------------------------------------- exact arithmetic for doubles

namespace {

using W = WideInt<10>;


template <int R, int C> Eigen::Matrix<Q, R, C> rational(const Eigen::Matrix<W, R, C>& m, const Q& scale) {
  Eigen::Matrix<Q, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = m(i).to_rational() * scale;
  return out;
}

/// The double-valued item as integers (as `qverify bench` does): A = A_int 2^eA, L = L_int 2^eL.
void to_wide(const double (&a)[10], const double (&l)[4], Mat4<W>& A, Vec4<W>& L, int& eA, int& eL) {
  W ai[10], li[4];
  eA = wide_from_doubles<10>(a, 10, ai);
  eL = wide_from_doubles<10>(l, 4, li);
  for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = ai[k];
  for (int k = 0; k < 4; ++k) L(k) = li[k];
}

void check_against_rationals(const double (&a)[10], const double (&l)[4]) {
  Mat4<W> A;
  Vec4<W> L;
  int eA, eL;
  to_wide(a, l, A, L, eA, eL);
  Mat4<Q> Aq;
  Vec4<Q> Lq;
  for (int k = 0; k < 10; ++k) Aq(kSymRow[k], kSymCol[k]) = Aq(kSymCol[k], kSymRow[k]) = Q(a[k]);
  for (int k = 0; k < 4; ++k) Lq(k) = Q(l[k]);
  // the bench's formulas, on WideInt and on rationals
  const Vec4<W> p = polar_plane<W>(A, L);
  const Vec4<Q> pq = polar_plane<Q>(Aq, Lq);
  CHECK(rational(p, pow2(eA + eL)) == pq);
  CHECK(rational(Mat4<W>(tangent_cone_from_polar<W>(A, L, p)), pow2(2 * eA + 2 * eL)) == tangent_cone<Q>(Aq, Lq));
  CHECK(rational(Mat4<W>(terminator_quadric_from_polar<W>(L, p)), pow2(eA + 2 * eL)) == terminator_quadric<Q>(Aq, Lq));
  if (Lq.head<3>().isZero()) return;  // no mirror plane
  CHECK(rational(Mat4<W>(scaled_mirror_matrix<W>(L)), pow2(2 * eL)) == scaled_mirror_matrix<Q>(Lq));
  const Mat4<Q> B = mirror_image<Q>(Aq, scaled_mirror_matrix<Q>(Lq));
  CHECK(rational(Mat4<W>(mirror_image_division_free<W>(A, L)), pow2(eA + 4 * eL)) == B);
  // (n.n)^2 times the reflection proper
  const Q nn = Lq.head<3>().squaredNorm();
  CHECK(B == Mat4<Q>(nn * nn * mirror_image_of_plane<Q>(Aq, Lq)));
}

}  // namespace

TEST_CASE("WideInt: + - * and comparisons equal GMP on random operands, carries and borrows", "[wide]") {
  using boost::multiprecision::mpz_int;
  std::mt19937_64 g(11);
  auto random_wide = [&](int limbs) {
    // limbs of random bits, all ones, or zero runs (carries and borrows through every limb)
    unsigned __int128 lo = (static_cast<unsigned __int128>(g()) << 64) | g();
    const int kind = static_cast<int>(g() % 3);
    if (kind == 1) lo = ~static_cast<unsigned __int128>(0);
    if (kind == 2) lo = static_cast<unsigned __int128>(1) << 64;
    W w = W::from_magnitude(lo, g() & 1, static_cast<int>(g() % 64));
    for (int k = 2; k < limbs; k += 2) w = w * W::from_magnitude(lo | 1, false, 0);
    return w;
  };
  for (int trial = 0; trial < 3000; ++trial) {
    const W a = random_wide(1 + static_cast<int>(g() % 4)), b = random_wide(1 + static_cast<int>(g() % 4));
    const Q qa = a.to_rational(), qb = b.to_rational();
    CHECK((a + b).to_rational() == qa + qb);
    CHECK((a - b).to_rational() == qa - qb);
    CHECK((b - a).to_rational() == qb - qa);
    CHECK((a - a).sign() == 0);
    if (a.limbs() + b.limbs() <= W::max_limbs + 1) {
      try {
        CHECK((a * b).to_rational() == qa * qb);
      } catch (const WideIntOverflow&) {
        CHECK(abs(qa * qb) >= pow2(64 * W::max_limbs));  // thrown only when it does not fit
      }
    }
    CHECK((a < b) == (qa < qb));
    CHECK((a == b) == (qa == qb));
    CHECK((-a).to_rational() == -qa);
  }
  // nothing is truncated: a product beyond the limbs throws
  const W big = W::from_magnitude(1, false, 64 * W::max_limbs - 2);
  CHECK_THROWS_AS(big * big, WideIntOverflow);
  CHECK_THROWS_AS(W::from_magnitude(1, false, 64 * W::max_limbs), WideIntOverflow);
}

TEST_CASE("WideInt: a double read from its bits is exactly the double, subnormals and extremes included", "[wide]") {
  const double tiny = std::numeric_limits<double>::denorm_min(), least_normal = std::numeric_limits<double>::min();
  const double values[] = {1.0, -1.0, 0.5, 3.0, 0.1, -1e300, std::numeric_limits<double>::max(), least_normal,
                           -least_normal, tiny, -tiny, 3 * tiny, least_normal - tiny, std::nextafter(1.0, 2.0),
                           std::ldexp(1.0, -1000), -std::ldexp(0x1.fffffffffffffp0, 30)};
  for (double x : values) {
    INFO(x);
    const int e = binary_exponent(x);
    const Q q = Q(x);
    // x = m 2^e with an integer m below 2^53, at e and at every smaller exponent
    for (int e0 : {e, e - 1, e - 77}) {
      const W m = wide_from_double<10>(x, e0);
      CHECK(m.bits() <= 53 + (e - e0));
      CHECK(m.to_rational() * pow2(e0) == q);
    }
  }
  CHECK(binary_exponent(tiny) == -1074);
  CHECK(binary_exponent(1.0) == -52);
  CHECK(wide_from_double<10>(0.0, -5).sign() == 0);
  CHECK(binary_exponent(0.0) > binary_exponent(std::numeric_limits<double>::max()));  // never the smallest
  CHECK_THROWS_AS(binary_exponent(std::numeric_limits<double>::infinity()), std::invalid_argument);
  CHECK_THROWS_AS(wide_from_double<10>(std::numeric_limits<double>::quiet_NaN(), 0), std::invalid_argument);
  CHECK_THROWS_AS(wide_from_double<10>(1.0, 0), std::invalid_argument);  // e0 above the double's exponent
  // a matrix's entries at one scale: the smallest exponent among them
  W out[3];
  const double mixed[3] = {0.75, -3.0, 0.0};
  const int e = wide_from_doubles<10>(mixed, 3, out);
  CHECK(e == binary_exponent(0.75));
  for (int k = 0; k < 3; ++k) CHECK(out[k].to_rational() * pow2(e) == Q(mixed[k]));
  const double zeros[2] = {0.0, -0.0};
  CHECK(wide_from_doubles<10>(zeros, 2, out) == 0);
  CHECK(out[0].sign() == 0);
  CHECK(out[1].sign() == 0);
  const double spread[2] = {1.0, std::ldexp(1.0, -700)};  // 700 + 53 bits: beyond 640, refused
  CHECK_THROWS_AS(wide_from_doubles<10>(spread, 2, out), WideIntOverflow);
}

TEST_CASE("WideInt: the direct formulas on double-valued items equal GMP rationals", "[wide]") {
  std::mt19937_64 g(12);
  for (int trial = 0; trial < 60; ++trial) {
    double a[10], l[4];
    const int spread = trial < 40 ? 30 : 60;  // the bench's spread, and wider
    for (double& v : a) v = random_double(g, spread);
    for (int k = 0; k < 3; ++k) l[k] = random_double(g, spread);
    l[3] = 1;
    // adversarial entries: zeros, subnormals, exact cancellation (pi_0 = 0 below)
    if (trial % 5 == 1) a[g() % 10] = 0, l[g() % 3] = 0;
    if (trial % 7 == 2) a[3] = 4.9406564584124654e-324, a[0] = -std::ldexp(1.0, -1070);
    if (trial % 6 == 3) {  // A row 0 . L == 0 exactly: a0 l0 + a1 l1 + a2 l2 + a3 = 0
      l[0] = 1, l[1] = 2, l[2] = 4, a[0] = 8, a[1] = 4, a[2] = -2, a[3] = -8;
    }
    INFO("trial " << trial);
    Mat4<W> A;
    Vec4<W> L;
    int eA, eL;
    try {
      to_wide(a, l, A, L, eA, eL);
    } catch (const WideIntOverflow&) {
      // an entry's shift beyond the limbs (a subnormal beside 2^30): refused, never truncated
      int lo = 100000, hi = -100000;
      for (double v : a)
        if (v != 0) lo = std::min(lo, binary_exponent(v)), hi = std::max(hi, binary_exponent(v));
      CHECK(hi - lo + 53 > 64 * W::max_limbs - 128);
      continue;
    }
    int bA = 0, bL = 0;
    for (Eigen::Index i = 0; i < 16; ++i) bA = std::max(bA, A(i).bits());
    for (int i = 0; i < 4; ++i) bL = std::max(bL, L(i).bits());
    if (2 * bA + 2 * bL + 5 > 640 || bA + 4 * bL + 8 > 640) {
      // beyond WideInt<10> (subnormals next to 2^30): the formulas must throw, never truncate
      bool threw = false;
      try {
        (void)tangent_cone<W>(A, L);
        (void)mirror_image_division_free<W>(A, L);
      } catch (const WideIntOverflow&) {
        threw = true;
      }
      if (!threw) check_against_rationals(a, l);  // it fitted after all: then it is exact
      continue;
    }
    check_against_rationals(a, l);
  }
}

TEST_CASE("WideInt: decimal text scaled to a power of ten equals GMP rationals", "[wide]") {
  std::mt19937_64 g(13);
  for (int trial = 0; trial < 40; ++trial) {
    std::int64_t m[14];
    int e[14];
    for (int k = 0; k < 14; ++k) {
      m[k] = static_cast<std::int64_t>(10000000000000000ull + g() % 90000000000000000ull) * ((g() & 1) ? -1 : 1);
      e[k] = static_cast<int>(g() % 18) - 25;
    }
    m[13] = 1, e[13] = 0;  // w = 1
    if (trial % 4 == 1) m[g() % 10] = 0;
    if (trial % 5 == 2) e[g() % 10] += 40;  // a shift beyond 10^38
    int kA = e[0], kL = e[10];
    for (int k = 0; k < 10; ++k) kA = std::min(kA, e[k]);
    for (int k = 10; k < 14; ++k) kL = std::min(kL, e[k]);
    Mat4<W> A;
    Vec4<W> L;
    Mat4<Q> Aq;
    Vec4<Q> Lq;
    for (int k = 0; k < 10; ++k) {
      A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = wide_from_decimal<10>(m[k], e[k] - kA);
      Aq(kSymRow[k], kSymCol[k]) = Aq(kSymCol[k], kSymRow[k]) = Q(m[k]) * pow10(e[k]);
      CHECK(A(kSymRow[k], kSymCol[k]).to_rational() * pow10(kA) == Aq(kSymRow[k], kSymCol[k]));
    }
    for (int k = 0; k < 4; ++k) {
      L(k) = wide_from_decimal<10>(m[10 + k], e[10 + k] - kL);
      Lq(k) = Q(m[10 + k]) * pow10(e[10 + k]);
    }
    INFO("trial " << trial);
    Mat4<Q> P, B;
    bool threw = false;
    try {
      P = rational(Mat4<W>(tangent_cone<W>(A, L)), pow10(2 * kA + 2 * kL));
      B = rational(Mat4<W>(mirror_image_division_free<W>(A, L)), pow10(kA + 4 * kL));
    } catch (const WideIntOverflow&) {
      threw = true;
    }
    if (threw) {
      CHECK(trial % 5 == 2);  // only the items with a shift beyond the bench's range may not fit
      continue;
    }
    CHECK(P == tangent_cone<Q>(Aq, Lq));
    CHECK(B == mirror_image<Q>(Aq, scaled_mirror_matrix<Q>(Lq)));
  }
}

TEST_CASE("mirror_image_division_free equals M'^T A M' for the division-free mirror matrix", "[wide]") {
  std::mt19937_64 g(14);
  for (int trial = 0; trial < 50; ++trial) {
    Mat4<__int128> A;
    Vec4<__int128> w;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) A(i, j) = A(j, i) = static_cast<__int128>(g() % 201) - 100;
    for (int i = 0; i < 4; ++i) w(i) = static_cast<__int128>(g() % 41) - 20;
    if (w(0) == 0 && w(1) == 0 && w(2) == 0) w(0) = 1;
    const bool same = mirror_image_division_free<__int128>(A, w) == mirror_image<__int128>(A, scaled_mirror_matrix<__int128>(w));
    CHECK(same);
    const Mat4<Q> Aq = A.unaryExpr([](__int128 v) { return Q(static_cast<long>(v)); });
    const Vec4<Q> wq = w.unaryExpr([](__int128 v) { return Q(static_cast<long>(v)); });
    CHECK(mirror_image_division_free<Q>(Aq, wq) == mirror_image<Q>(Aq, scaled_mirror_matrix<Q>(wq)));
  }
}
