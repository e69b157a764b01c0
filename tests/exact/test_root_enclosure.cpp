// exact/root_enclosure.hpp: the filters' second stage. Every enclosure is checked exactly
// (its bounds as dyadic rationals against u + v sqrt(d) by root_sign), on both of its paths
// (the direct difference and the exact norm), and it must be tight enough to rank points.
#include <qverify/exact/root_enclosure.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace qverify;

namespace {

/// sign(|u + v sqrt(d)| - m 2^e) exactly, for the MPFR number m 2^e >= 0.
int compare_abs(const BigInt& u, const BigInt& v, const BigInt& d, mpfr_srcptr bound) {
  if (mpfr_zero_p(bound)) return root_sign(u, v, d) != 0;  // (its exponent would be MPFR's least)
  BigInt m;
  const mpfr_exp_t e = mpfr_get_z_2exp(mpz(m), bound);
  BigInt a = m, b = 1;  // bound = a / b
  if (e >= 0) mpz_mul_2exp(mpz(a), mpz(a), static_cast<mp_bitcnt_t>(e));
  else mpz_mul_2exp(mpz(b), mpz(b), static_cast<mp_bitcnt_t>(-e));
  const int s = root_sign(u, v, d) < 0 ? -1 : 1;
  // s (u + v sqrt(d)) - a / b, times b > 0
  return root_sign(BigInt(s * u * b - a), BigInt(s * v * b), d);
}

struct Bounds {
  mpfr_t lo, hi;
  explicit Bounds(mpfr_prec_t bits) { mpfr_init2(lo, bits), mpfr_init2(hi, bits); }
  ~Bounds() { mpfr_clear(lo), mpfr_clear(hi); }
};

/// Encloses |u + v sqrt(d)| (into bounds of `out_bits`, default the working precision) and
/// checks that it holds and how wide it is; `root` false: v sqrt(d) is ignored (a rational point).
void check(RootEnclosure& e, mpfr_prec_t bits, const BigInt& u, const BigInt& v, const BigInt& d, bool root = true,
           mpfr_prec_t out_bits = 0) {
  Bounds b(out_bits ? out_bits : bits);
  e.set_radicand(d);
  e.enclose(b.lo, b.hi, u, v, root);
  if (!root) {  // |u| alone
    CHECK(compare_abs(u, BigInt(0), d, b.lo) >= 0);
    CHECK(compare_abs(u, BigInt(0), d, b.hi) <= 0);
    return;
  }
  INFO("u = " << u << ", v = " << v << ", d = " << d);
  REQUIRE(mpfr_sgn(b.lo) >= 0);
  CHECK(compare_abs(u, v, d, b.lo) >= 0);
  CHECK(compare_abs(u, v, d, b.hi) <= 0);
  if (root_sign(u, v, d) == 0) return;
  // tight: a few units of the last place, or 2^-kTightBits where the difference was kept directly
  Bounds w(bits);
  mpfr_sub(w.lo, b.hi, b.lo, MPFR_RNDU);
  mpfr_mul_2si(w.hi, b.lo, -RootEnclosure::kTightBits, MPFR_RNDD);
  CHECK(mpfr_lessequal_p(w.lo, w.hi));
}

BigInt random_int(std::mt19937_64& gen, int bits) {
  BigInt x = 0;
  for (int b = 0; b < bits; b += 64) {
    mpz_mul_2exp(mpz(x), mpz(x), 64);
    x += BigInt(gen());
  }
  mpz_fdiv_q_2exp(mpz(x), mpz(x), static_cast<mp_bitcnt_t>((64 - bits % 64) % 64));
  return (gen() & 1) ? BigInt(-x) : x;
}

}  // namespace

TEST_CASE("root enclosures hold exactly and are tight on both paths", "[exact][enclosure][filter]") {
  std::mt19937_64 gen(31);
  for (const mpfr_prec_t bits : {64, 128}) {
    RootEnclosure e(bits);
    for (int trial = 0; trial < 60; ++trial) {
      const int size = 20 + static_cast<int>(gen() % 3000);
      const BigInt d = abs(random_int(gen, 1 + static_cast<int>(gen() % 4000)));
      const BigInt u = random_int(gen, size), v = random_int(gen, size / 2 + 1);
      check(e, bits, u, v, d);                   // random signs: either path
      check(e, bits, u, BigInt(0), d);           // rational
      check(e, bits, BigInt(0), v, d);           // a pure root
      // deep cancellation: u the integer nearest -v sqrt(d) (the exact norm's path)
      BigInt r;
      mpz_mul(mpz(r), mpz(v), mpz(v));
      mpz_mul(mpz(r), mpz(r), mpz(d));
      mpz_sqrt(mpz(r), mpz(r));
      const BigInt near = v > 0 ? BigInt(-r) : r;
      check(e, bits, near, v, d);
      check(e, bits, BigInt(near + 1), v, d);
      // mild cancellation: u - v sqrt(d) about 2^-40 of u (the direct path at 128 bits)
      mpz_fdiv_q_2exp(mpz(r), mpz(r), 40);
      check(e, bits, BigInt(near + (v > 0 ? BigInt(-r) : r)), v, d);
    }
    // the direct difference with an inexact subtraction (|u| far above |v| sqrt(d), both below
    // 2^bits): a wrong rounding direction there shows
    for (int trial = 0; trial < 200; ++trial) {
      const BigInt u = abs(random_int(gen, static_cast<int>(bits) - 4)) + 1;
      const BigInt d = 2 + gen() % 100000, v = -BigInt(1 + gen() % 1000);
      check(e, bits, u, v, d);
      check(e, bits, BigInt(-u), BigInt(-v), d);
      check(e, bits, u, v, d, true, bits + 7);  // into bounds of another precision
      check(e, bits, u, v, d, true, bits - 9);
    }
    check(e, bits, BigInt(12345), BigInt(77), BigInt(0));          // d = 0: v sqrt(d) = 0
    check(e, bits, BigInt(-12345), BigInt(77), BigInt(3), false);  // a rational point: v ignored
    // a perfect square: u + v sqrt(d) exactly 0
    check(e, bits, BigInt(-21), BigInt(7), BigInt(9));
    check(e, bits, BigInt(0), BigInt(0), BigInt(5));
  }
}
