// The exact arithmetic for doubles and decimal text (exact/wide_int.hpp, and the division-free
// mirror image of core/mirror_division_free.hpp it runs) against GMP rationals. Speed is not
// tested here: `qverify bench` and bench/bench_wide measure it.
#include <qverify/core/core.hpp>
#include <qverify/batch/rows.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/exact/wide_int.hpp>

#include "laws.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

using namespace qverify;
using qverify::test::pow10;
using qverify::test::pow2;
using qverify::test::random_double;

namespace {

using Q = Rational;
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
  // x += x and x -= x in place, as GMP
  for (int trial = 0; trial < 200; ++trial) {
    W a = random_wide(1 + static_cast<int>(g() % 4));
    const Q qa = a.to_rational();
    W b = a;
    b += b;
    CHECK(b.to_rational() == 2 * qa);
    b -= b;
    CHECK(b.sign() == 0);
  }
  // the most negative value of one limb, -2^63 (a sum that just fits), and its negation (one more limb)
  const W m62 = W::from_magnitude(static_cast<unsigned __int128>(1) << 62, true);
  const W m63 = m62 + m62;
  CHECK(m63.limbs() == 1);
  CHECK(m63.to_rational() == -pow2(63));
  CHECK((-m63).to_rational() == pow2(63));
  CHECK((m63 * m63).to_rational() == pow2(126));
  CHECK((m63 - W(1)).to_rational() == -pow2(63) - 1);
  // a sum beyond the limbs throws: 2^638 + 2^638 needs a 641st bit with the sign
  const W half = W::from_magnitude(1, false, 64 * W::max_limbs - 2);
  CHECK(half.limbs() == W::max_limbs);
  CHECK_THROWS_AS(half + half, WideIntOverflow);
  CHECK((half - half).sign() == 0);
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
    if (2 * bA + 2 * bL + 5 > 639 || bA + 4 * bL + 8 > 639) {  // two's complement: 639 bits and a sign
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
