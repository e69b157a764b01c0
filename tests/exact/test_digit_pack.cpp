// DigitPack (exact/digit_pack.hpp): W items' exact integers at once, lane by lane against GMP
// rationals: the operations with and without normalization, reading doubles, the direct
// formulas on double-valued items, decisions across lanes, and overflow. Speed is not tested
// here: `qverify bench` and bench/bench_wide measure it.
#include <qverify/batch/rows.hpp>
#include <qverify/core/core.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/exact/digit_batch.hpp>
#include <qverify/exact/digit_pack.hpp>
#include <qverify/exact/wide_int.hpp>

#include "dispatch_check.hpp"
#include "laws.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace qverify;
using qverify::test::pow10;
using qverify::test::pow2;
using qverify::test::random_double;

namespace {

using Q = Rational;
using DP = DigitPack<24>;
constexpr int kL = DP::lanes;

Q q128(__int128 v) {
  const bool negative = v < 0;
  const unsigned __int128 m = negative ? -static_cast<unsigned __int128>(v) : static_cast<unsigned __int128>(v);
  boost::multiprecision::mpz_int z = static_cast<std::uint64_t>(m >> 64);
  z <<= 64;
  z += static_cast<std::uint64_t>(m);
  return negative ? Q(-z) : Q(z);
}

/// Random lanes: random bits of a random length, all ones, a power of two, zero, and the extremes.
__int128 random_lane(std::mt19937_64& g) {
  const int bits = 1 + static_cast<int>(g() % 126);
  unsigned __int128 m = (static_cast<unsigned __int128>(g()) << 64) | g();
  switch (g() % 6) {
    case 0: m = ~static_cast<unsigned __int128>(0); break;
    case 1: m = static_cast<unsigned __int128>(1) << (bits - 1); break;
    case 2: m = 0; break;
    default: break;
  }
  m &= (static_cast<unsigned __int128>(1) << bits) - 1;
  const auto v = static_cast<__int128>(m);
  return (g() & 1) ? -v : v;
}

struct Lanes {
  DP p;
  Q q[kL];
};

Lanes random_pack(std::mt19937_64& g) {
  __int128 v[kL];
  for (auto& x : v) x = random_lane(g);
  Lanes r;
  r.p = DP::from_lanes(v);
  for (int l = 0; l < kL; ++l) r.q[l] = q128(v[l]);
  return r;
}

void check_lanes(const DP& p, const Q (&q)[kL]) {
  for (int l = 0; l < kL; ++l) {
    INFO("lane " << l);
    CHECK(p.to_rational(l) == q[l]);
    CHECK(abs(q[l]) < pow2(p.bound_bits()));
  }
}

template <int R, int C> Eigen::Matrix<Q, R, C> lane(const Eigen::Matrix<DP, R, C>& m, int l, const Q& scale) {
  Eigen::Matrix<Q, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = m(i).to_rational(l) * scale;
  return out;
}

}  // namespace

TEST_CASE("DigitPack: + - * lane by lane equal GMP, through lazy digits and normalizations", "[digit]") {
  std::mt19937_64 g(21);
  for (int trial = 0; trial < 400; ++trial) {
    Lanes a = random_pack(g), b = random_pack(g);
    check_lanes(a.p, a.q);
    // a chain: sums of products of sums (digits grow lazily; products normalize their operands)
    for (int step = 0; step < 6; ++step) {
      const Lanes c = random_pack(g);
      Lanes r;
      const int op = static_cast<int>(g() % 4);
      if (a.p.bound_bits() + std::max(b.p.bound_bits(), c.p.bound_bits()) > DP::max_bits - 64) break;
      switch (op) {
        case 0: r.p = a.p + b.p; for (int l = 0; l < kL; ++l) r.q[l] = a.q[l] + b.q[l]; break;
        case 1: r.p = a.p - c.p; for (int l = 0; l < kL; ++l) r.q[l] = a.q[l] - c.q[l]; break;
        case 2: r.p = a.p * b.p; for (int l = 0; l < kL; ++l) r.q[l] = a.q[l] * b.q[l]; break;
        default: r.p = -(a.p * c.p) + b.p; for (int l = 0; l < kL; ++l) r.q[l] = -(a.q[l] * c.q[l]) + b.q[l]; break;
      }
      INFO("trial " << trial << " step " << step << " op " << op);
      check_lanes(r.p, r.q);
      b = a;
      a = r;
    }
  }
}

TEST_CASE("DigitPack: chains of lazy operands, never read until the end, equal GMP", "[digit]") {
  // the bounds that decide when an operand is normalized (a digit product reads 32 bits; a digit's
  // products must sum below 2^63; a sum adds a bit) are met only if nothing in between normalizes:
  // here nothing is read between the operations
  std::mt19937_64 g(27);
  for (int trial = 0; trial < 300; ++trial) {
    __int128 top[kL];
    for (auto& v : top) v = (static_cast<__int128>(1) << (60 + g() % 60)) - 1;  // all digits 2^28 - 1
    Lanes x = random_pack(g), y = random_pack(g);
    if (trial % 2) {
      x.p = DP::from_lanes(top);
      for (int l = 0; l < kL; ++l) x.q[l] = q128(top[l]);
    }
    DP acc = x.p;
    Q q[kL];
    for (int l = 0; l < kL; ++l) q[l] = x.q[l];
    const int adds = static_cast<int>(g() % 40);
    for (int k = 0; k < adds; ++k) {  // digits up to 2^(28 + adds)
      if (k % 3 == 2) acc -= y.p;
      else acc += acc;
      for (int l = 0; l < kL; ++l) q[l] = k % 3 == 2 ? q[l] - y.q[l] : q[l] + q[l];
      if (acc.bound_bits() > 200) break;
    }
    DP prod = acc * acc;  // lazy times lazy, itself
    prod += x.p * y.p;
    prod -= acc;
    DP neg = -prod;
    neg *= x.p;
    for (int l = 0; l < kL; ++l) q[l] = -((q[l] * q[l] + x.q[l] * y.q[l] - q[l]) * x.q[l]);
    INFO("trial " << trial << ", " << adds << " sums");
    check_lanes(neg, q);
  }
}

TEST_CASE("DigitPack: digits at their bound, doubled up to 2^32, multiplied", "[digit]") {
  // every digit 2^28 - 1 doubled d times is 2^(28 + d) - 2^d: the largest a digit of bound 2^(28 + d)
  // gets. A digit product reads 32 bits, signed: at d = 3 the digits are just below 2^31 and are
  // multiplied as they are; at d = 4 (2^32 - 16) they must be normalized first, or they are read wrong.
  std::mt19937_64 g(41);
  for (int d = 0; d <= 6; ++d)
    for (int trial = 0; trial < 8; ++trial) {
      __int128 top[kL];
      for (auto& v : top) v = ((g() % 2) ? 1 : -1) * ((static_cast<__int128>(1) << (56 + g() % 40)) - 1);
      DP x = DP::from_lanes(top);
      Q q[kL];
      for (int l = 0; l < kL; ++l) q[l] = q128(top[l]);
      for (int k = 0; k < d; ++k) x += x;
      const Lanes y = random_pack(g);
      DP prod = x * y.p;
      DP square = x * x;
      Q qp[kL], qs[kL];
      for (int l = 0; l < kL; ++l) qp[l] = q[l] * pow2(d) * y.q[l], qs[l] = q[l] * q[l] * pow2(2 * d);
      INFO(d << " doublings");
      check_lanes(prod, qp);
      check_lanes(square, qs);
    }
}

TEST_CASE("DigitPack: normalize keeps the value and bounds every digit by 2^28", "[digit]") {
  std::mt19937_64 g(22);
  for (int trial = 0; trial < 200; ++trial) {
    const Lanes a = random_pack(g), b = random_pack(g);
    DP s = a.p * b.p;
    for (int k = 0; k < 20; ++k) s = s + s;  // lazy digits up to about 2^(56 + 3 + 20)
    Q q[kL];
    for (int l = 0; l < kL; ++l) q[l] = a.q[l] * b.q[l] * pow2(20);
    s.normalize();
    check_lanes(s, q);
    CHECK(s.digits() == DP::digits_for(s.bound_bits()));
    const std::int64_t radix = std::int64_t(1) << DP::radix_bits;
    for (int l = 0; l < kL; ++l) {
      for (int k = 0; k + 1 < s.digits(); ++k) CHECK((s.digit(k, l) >= 0 && s.digit(k, l) < radix));
      CHECK(std::abs(s.digit(s.digits() - 1, l)) <= radix);
    }
    // the digits themselves: read back through the same form by a second normalization
    DP t = s;
    t.normalize();
    for (int l = 0; l < kL; ++l) CHECK(t.to_rational(l) == q[l]);
  }
  // x - x is zero in every lane, whatever its digits
  const Lanes a = random_pack(g);
  int signs[kL];
  (a.p - a.p).signs(signs);
  for (int l = 0; l < kL; ++l) CHECK(signs[l] == 0);
}

TEST_CASE("DigitPack: doubles read exactly, lanes at their own exponents", "[digit]") {
  std::mt19937_64 g(23);
  const double tiny = std::numeric_limits<double>::denorm_min();
  for (int trial = 0; trial < 300; ++trial) {
    double x[kL][6];
    for (auto& item : x)
      for (double& v : item) v = random_double(g, trial % 2 ? 30 : 5);
    if (trial % 7 == 1) x[0][2] = 0.0, x[kL - 1][0] = -0.0;
    if (trial % 11 == 3) {  // an item of subnormals and numbers near them
      for (double& v : x[1 % kL]) v = std::ldexp(random_double(g, 5), -1040);
      x[1 % kL][4] = -tiny * 3;
    }
    if (trial % 13 == 4)
      for (double& v : x[0]) v = 0.0;  // an item of zeros
    const double* items[kL];
    for (int l = 0; l < kL; ++l) items[l] = x[l];
    DP out[6];
    int e[kL];
    INFO("trial " << trial);
    REQUIRE(DP::from_doubles(items, 6, out, e));
    for (int k = 0; k < 6; ++k)
      for (int l = 0; l < kL; ++l) {
        CHECK(out[k].to_rational(l) * pow2(e[l]) == Q(x[l][k]));
        CHECK(abs(Q(x[l][k])) < pow2(out[k].bound_bits() + e[l]));  // the bit bound holds
      }
  }
  // a spread beyond 126 bits is refused, inf and NaN are errors
  double wide[kL][2], bad[kL][2];
  for (int l = 0; l < kL; ++l) wide[l][0] = bad[l][0] = 1.0, wide[l][1] = bad[l][1] = 2.0;
  wide[kL - 1][1] = std::ldexp(1.0, 80);
  bad[0][1] = std::numeric_limits<double>::quiet_NaN();
  const double* w[kL];
  const double* b[kL];
  for (int l = 0; l < kL; ++l) w[l] = wide[l], b[l] = bad[l];
  DP out[2];
  int e[kL];
  CHECK_FALSE(DP::from_doubles(w, 2, out, e));
  CHECK_THROWS_AS(DP::from_doubles(b, 2, out, e), std::invalid_argument);
}

TEST_CASE("DigitPack: the direct formulas on double-valued items equal GMP rationals, lane by lane", "[digit]") {
  std::mt19937_64 g(24);
  for (int trial = 0; trial < 40; ++trial) {
    double a[kL][10], l[kL][4];
    for (int i = 0; i < kL; ++i) {
      for (double& v : a[i]) v = random_double(g, trial < 30 ? 30 : 36);
      for (int k = 0; k < 3; ++k) l[i][k] = random_double(g, trial < 30 ? 30 : 36);
      l[i][3] = 1;
      if ((trial + i) % 5 == 1) a[i][g() % 10] = 0, l[i][g() % 3] = 0;  // zeros
    }
    if (trial % 6 == 3) {  // A row 0 . L == 0 exactly in lane 0: pi_0 cancels
      l[0][0] = 1, l[0][1] = 2, l[0][2] = 4, a[0][0] = 8, a[0][1] = 4, a[0][2] = -2, a[0][3] = -8;
    }
    const double* ai[kL];
    const double* li[kL];
    for (int i = 0; i < kL; ++i) ai[i] = a[i], li[i] = l[i];
    DP A10[10], L4[4];
    int eA[kL], eL[kL];
    REQUIRE(DP::from_doubles(ai, 10, A10, eA));
    REQUIRE(DP::from_doubles(li, 4, L4, eL));
    Mat4<DP> A;
    Vec4<DP> L;
    for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = A10[k];
    for (int k = 0; k < 4; ++k) L(k) = L4[k];
    const Vec4<DP> p = polar_plane<DP>(A, L);
    const Mat4<DP> P = tangent_cone_from_polar<DP>(A, L, p);
    const Mat4<DP> R = terminator_quadric_from_polar<DP>(L, p);
    const Mat4<DP> M = scaled_mirror_matrix<DP>(L);
    const Mat4<DP> B = mirror_image_division_free<DP>(A, L);
    for (int i = 0; i < kL; ++i) {
      INFO("trial " << trial << " lane " << i);
      Mat4<Q> Aq;
      Vec4<Q> Lq;
      for (int k = 0; k < 10; ++k) Aq(kSymRow[k], kSymCol[k]) = Aq(kSymCol[k], kSymRow[k]) = Q(a[i][k]);
      for (int k = 0; k < 4; ++k) Lq(k) = Q(l[i][k]);
      CHECK(lane(p, i, pow2(eA[i] + eL[i])) == polar_plane<Q>(Aq, Lq));
      CHECK(lane(P, i, pow2(2 * eA[i] + 2 * eL[i])) == tangent_cone<Q>(Aq, Lq));
      CHECK(lane(R, i, pow2(eA[i] + 2 * eL[i])) == terminator_quadric<Q>(Aq, Lq));
      if (Lq.head<3>().isZero()) continue;
      CHECK(lane(M, i, pow2(2 * eL[i])) == scaled_mirror_matrix<Q>(Lq));
      CHECK(lane(B, i, pow2(eA[i] + 4 * eL[i])) == mirror_image<Q>(Aq, scaled_mirror_matrix<Q>(Lq)));
    }
  }
}

TEST_CASE("DigitPack: decisions are taken when all lanes agree, MixedLanes otherwise", "[digit]") {
  __int128 zeros[kL] = {}, ones[kL], mixed[kL] = {};
  for (auto& v : ones) v = 1;
  mixed[kL - 1] = -5;
  const DP z = DP::from_lanes(zeros), o = DP::from_lanes(ones), m = DP::from_lanes(mixed);
  CHECK(m.to_rational(kL - 1) == -5);  // one digit, negative
  CHECK(m.to_rational(0) == 0);
  CHECK(equals_zero<DP>(z));
  CHECK_FALSE(equals_zero<DP>(o));
  CHECK_THROWS_AS(equals_zero<DP>(m), MixedLanes);
  CHECK(equals_zero<DP>(o - o));
  CHECK(less_than<DP>(z, o));
  CHECK_FALSE(less_than<DP>(o, z));
  CHECK_THROWS_AS(less_than<DP>(m, z), MixedLanes);
  CHECK(is_exact<DP>());
  // frame_plane asks whether L_w = 0: a block of point lights, of suns, and one mixing them
  Vec4<DP> L(o, o, o, o);
  CHECK(lane(Vec4<DP>(frame_plane<DP>(L)), 0, Q(1)) == Vec4<Q>(0, 0, 1, -1));
  L(3) = z;
  CHECK(lane(Vec4<DP>(frame_plane<DP>(L)), 0, Q(1)) == Vec4<Q>(0, 0, 0, 1));
  L(3) = m;
  CHECK_THROWS_AS(frame_plane<DP>(L), MixedLanes);
}

TEST_CASE("DigitPack: nothing is truncated, a result beyond the digits throws", "[digit]") {
  __int128 big[kL];
  for (auto& v : big) v = static_cast<__int128>(1) << 120;
  DP x = DP::from_lanes(big);
  // 2^120 has 5 digits: x^4 needs 17 and x^5 21 (of 24); x^6 (25) does not fit
  DP y = x * x * x * x * x;
  CHECK(y.to_rational(0) == pow2(600));
  CHECK_THROWS_AS(y * x, DigitPackOverflow);
  CHECK_THROWS_AS(DP::from_lanes(big, 100), std::invalid_argument);  // a bound below the values
  CHECK_THROWS_AS(DP::from_lanes(big, 0), std::invalid_argument);
}

TEST_CASE("DigitPack: decimal text m 10^k read exactly through 128-bit integers, lane by lane", "[digit]") {
  std::mt19937_64 g(25);
  for (int trial = 0; trial < 200; ++trial) {
    __int128 v[kL];
    Q q[kL];
    for (int l = 0; l < kL; ++l) {
      const auto m = static_cast<std::int64_t>(10000000000000000ull + g() % 90000000000000000ull) * ((g() & 1) ? -1 : 1);
      const int shift = static_cast<int>(g() % 19);  // 17 digits times up to 10^18: below 2^126
      REQUIRE(decimal_to_int128(m, shift, v[l]));
      q[l] = Q(m) * pow10(shift);
    }
    check_lanes(DP::from_lanes(v), q);
  }
  __int128 v = 0;
  CHECK(decimal_to_int128(0, 50, v));
  CHECK(v == 0);
  CHECK_FALSE(decimal_to_int128(1, 39, v));                              // beyond the table
  CHECK(decimal_to_int128(-85070591730234615, 21, v));                 // 8.5e37 < 2^126 = 8.507e37
  CHECK(q128(v) == Q(-85070591730234615) * pow10(21));
  CHECK_FALSE(decimal_to_int128(85070591730234616, 21, v));            // 8.5070591730234616e37 > 2^126
  CHECK_THROWS_AS(decimal_to_int128(1, -1, v), std::invalid_argument);
}

// ------------------------------------------------------------------ digit blocks (digit_batch.hpp)

TEST_CASE("digit blocks: every whole block's results equal GMP rationals, item by item", "[digit]") {
  std::mt19937_64 g(26);
  const int W = digit_blocks_lanes();
  const Eigen::Index n = 5 * W + 3;  // five blocks and three items left to the caller
  std::vector<double> a(static_cast<std::size_t>(10 * n)), l(static_cast<std::size_t>(4 * n));
  std::vector<std::int64_t> am(a.size()), lm(l.size());
  std::vector<int> ae(a.size()), le(l.size());
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    for (int k = 0; k < 10; ++k) {
      a[10 * u + k] = random_double(g, 30);
      am[10 * u + k] = static_cast<std::int64_t>(10000000000000000ull + g() % 90000000000000000ull) * ((g() & 1) ? -1 : 1);
      ae[10 * u + k] = static_cast<int>(g() % 18) - 25;
    }
    for (int k = 0; k < 4; ++k) {
      l[4 * u + k] = k == 3 ? 1.0 : random_double(g, 30);
      lm[4 * u + k] = k == 3 ? 1 : static_cast<std::int64_t>(1000000000000000ull + g() % 9000000000000000ull);
      le[4 * u + k] = k == 3 ? 0 : static_cast<int>(g() % 18) - 25;
    }
  }
  // block 2: an item whose entries span more than 126 bits (left to the caller)
  a[10 * static_cast<std::size_t>(2 * W + 1)] = std::ldexp(1.0, 200);
  // block 3: lanes that disagree on L_w = 0 (a parallel light among point lights: left to the caller)
  l[4 * static_cast<std::size_t>(3 * W) + 3] = 0.0;
  for (const DigitOp op : {DigitOp::shadow, DigitOp::reflection}) {
    DigitBlocks out;
    CHECK(digit_blocks(op, DoubleItems{a.data(), l.data(), n}, out) == (op == DigitOp::shadow ? 2 : 1));
    DigitBlocks dec;
    CHECK(digit_blocks(op, DecimalItems{am.data(), ae.data(), lm.data(), le.data(), n}, dec) == 0);
    REQUIRE(out.blocks() == 5);
    CHECK(out.lanes == W);
    CHECK(out.base == 2);
    CHECK(dec.base == 10);
    for (Eigen::Index i = 0; i < n; ++i) {
      INFO("item " << i << (op == DigitOp::shadow ? " shadow" : " reflection"));
      const auto u = static_cast<std::size_t>(i);
      const Eigen::Index b = i / W;
      const bool whole = b < out.blocks();
      const bool undone = b == 2 || (op == DigitOp::shadow && b == 3);
      if (!whole) continue;
      CHECK(static_cast<bool>(out.done[static_cast<std::size_t>(b)]) == !undone);
      for (const bool decimal : {false, true}) {
        const DigitBlocks& r = decimal ? dec : out;
        if (!decimal && undone) {
          CHECK_THROWS_AS(r.value(i, 0), std::logic_error);
          continue;
        }
        Mat4<Q> A;
        Vec4<Q> L;
        for (int k = 0; k < 10; ++k)
          A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) =
              decimal ? Q(am[10 * u + k]) * test::pow10(ae[10 * u + k]) : Q(a[10 * u + k]);
        for (int k = 0; k < 4; ++k) L(k) = decimal ? Q(lm[4 * u + k]) * test::pow10(le[4 * u + k]) : Q(l[4 * u + k]);
        if (op == DigitOp::shadow) {
          const Mat4<Q> P = tangent_cone<Q>(A, L), R = terminator_quadric<Q>(A, L);
          const Vec4<Q> p = polar_plane<Q>(A, L);
          for (int k = 0; k < 10; ++k) CHECK(r.value(i, k) == P(kSymRow[k], kSymCol[k]));
          for (int k = 0; k < 4; ++k) CHECK(r.value(i, 10 + k) == p(k));
          for (int k = 0; k < 10; ++k) CHECK(r.value(i, 14 + k) == R(kSymRow[k], kSymCol[k]));
        } else {
          const Mat4<Q> M = scaled_mirror_matrix<Q>(L), B = mirror_image<Q>(A, M);
          for (int k = 0; k < 12; ++k) CHECK(r.value(i, k) == M(k / 4, k % 4));
          for (int k = 0; k < 10; ++k) CHECK(r.value(i, 12 + k) == B(kSymRow[k], kSymCol[k]));
        }
      }
    }
    CHECK_THROWS_AS(out.value(n - 1, 0), std::out_of_range);  // not in a whole block
    CHECK_THROWS_AS(out.value(0, out.entries), std::out_of_range);
  }
  // the kernel that ran is the one the build chose and this processor runs (a dispatch that fell
  // back to the build's kernel would pass every comparison above)
  const std::string second = digit_blocks_second_kernel();
  test::check_dispatch(second, digit_blocks_dispatched(), digit_blocks_kernel());
  if (digit_blocks_dispatched()) CHECK(W == (second == "x86-64-v4" ? 8 : 4));
  a[0] = std::numeric_limits<double>::infinity();
  DigitBlocks out;
  CHECK_THROWS_AS(digit_blocks(DigitOp::shadow, DoubleItems{a.data(), l.data(), n}, out), std::invalid_argument);
  CHECK(std::string(digit_blocks_kernel()).size() > 0);
}
