// Must precede every inclusion of mpfr.h (Boost's headers include it too).
#define MPFR_WANT_FLOAT128 1
#if defined(__clang__) && __clang_major__ < 15
#define _Float128 __float128  // clang 14 spells the binary128 type only as __float128
#endif
#include <mpfr.h>

#include <qverify/exact/rounding.hpp>

#include <cmath>
#include <limits>

namespace qverify {
namespace {

/// Rounds q to nearest in a binary format with `prec` bits of significand and
/// MPFR exponent range [emin, emax] (significand in [1/2, 1)), subnormals
/// included. Returns the MPFR value (caller clears it) via `out`.
void round_in_format(mpfr_t out, const Rational& q, mpfr_prec_t prec, mpfr_exp_t emin, mpfr_exp_t emax,
                     RoundingReport& rep, mpfr_rnd_t mode = MPFR_RNDN) {
  const mpfr_exp_t old_min = mpfr_get_emin(), old_max = mpfr_get_emax();
  mpfr_set_emin(emin);
  mpfr_set_emax(emax);
  mpfr_init2(out, prec);
  int inex = mpfr_set_q(out, q.backend().data(), mode);
  inex = mpfr_check_range(out, inex, mode);
  inex = mpfr_subnormalize(out, inex, mode);
  rep.inexact = rep.inexact || inex != 0;
  if (mpfr_inf_p(out)) rep.overflow = true;
  if (q != 0 && (mpfr_zero_p(out) || mpfr_get_exp(out) < emin + prec - 1)) rep.underflow = true;
  mpfr_set_emin(old_min);
  mpfr_set_emax(old_max);
}

/// The exact value of an MPFR number (every finite one is a dyadic rational).
Rational mpfr_to_rational(mpfr_srcptr t) {
  mpq_t r;
  mpq_init(r);
  mpfr_get_q(r, t);
  Rational out{r};
  mpq_clear(r);
  return out;
}

template <class F> Rational binary_to_rational(F x) {
  // Every finite binary float is m * 2^e with integer m: read it exactly through MPFR.
  mpfr_t t;
  mpfr_init2(t, 128);
  if constexpr (std::is_same_v<F, float> || std::is_same_v<F, double>) mpfr_set_d(t, static_cast<double>(x), MPFR_RNDN);
  else mpfr_set_ld(t, x, MPFR_RNDN);
  Rational out = mpfr_to_rational(t);
  mpfr_clear(t);
  return out;
}

}  // namespace

/// Rounds q to nearest in a binary format (see round_in_format) and reads the
/// result out with `get` (exact: the MPFR value already has the format's precision).
template <class F, class Get>
F round_to_format(const Rational& q, RoundingReport& rep, mpfr_prec_t prec, mpfr_exp_t emin, mpfr_exp_t emax, Get get) {
  mpfr_t t;
  round_in_format(t, q, prec, emin, emax, rep);
  const F f = get(t);
  mpfr_clear(t);
  return f;
}

template <> float round_rational<float>(const Rational& q, RoundingReport& rep) {
  return round_to_format<float>(q, rep, 24, -148, 128, [](mpfr_t t) { return mpfr_get_flt(t, MPFR_RNDN); });
}

template <> double round_rational<double>(const Rational& q, RoundingReport& rep) {
  return round_to_format<double>(q, rep, 53, -1073, 1024, [](mpfr_t t) { return mpfr_get_d(t, MPFR_RNDN); });
}

template <> long double round_rational<long double>(const Rational& q, RoundingReport& rep) {
  static_assert(std::numeric_limits<long double>::digits == 64, "x87 extended long double expected");
  return round_to_format<long double>(q, rep, 64, -16444, 16384, [](mpfr_t t) { return mpfr_get_ld(t, MPFR_RNDN); });
}

template <> Float128 round_rational<Float128>(const Rational& q, RoundingReport& rep) {
  return round_to_format<Float128>(q, rep, 113, -16493, 16384,
                                   [](mpfr_t t) { return Float128(mpfr_get_float128(t, MPFR_RNDN)); });
}

Interval enclose(const Rational& q) {
  // Fast path, well inside the normal range of a double: mpq_get_d truncates
  // towards zero (GMP's documented rounding), so q lies between it and the next
  // double away from zero, or is it exactly.
  const auto* v = q.backend().data();
  if (mpq_sgn(v) == 0) return Interval(0);
  const long bits = static_cast<long>(mpz_sizeinbase(mpq_numref(v), 2)) - static_cast<long>(mpz_sizeinbase(mpq_denref(v), 2));
  if (bits > -1000 && bits < 1000) {
    const double t = mpq_get_d(v);
    mpq_t back;
    mpq_init(back);
    mpq_set_d(back, t);
    const bool exact = mpq_equal(back, v) != 0;
    mpq_clear(back);
    if (exact) return Interval(t);
    const double away = std::nextafter(t, mpq_sgn(v) > 0 ? std::numeric_limits<double>::infinity()
                                                          : -std::numeric_limits<double>::infinity());
    return mpq_sgn(v) > 0 ? Interval(t, away) : Interval(away, t);
  }
  RoundingReport rep;
  mpfr_t lo, hi;
  round_in_format(lo, q, 53, -1073, 1024, rep, MPFR_RNDD);
  round_in_format(hi, q, 53, -1073, 1024, rep, MPFR_RNDU);
  const Interval r(mpfr_get_d(lo, MPFR_RNDD), mpfr_get_d(hi, MPFR_RNDU));
  mpfr_clear(lo);
  mpfr_clear(hi);
  return r;
}

template <> Interval round_rational<Interval>(const Rational& q, RoundingReport& rep) {
  const Interval r = enclose(q);
  if (!std::isfinite(r.inf()) || !std::isfinite(r.sup())) rep.overflow = true;
  if (r.inf() != r.sup()) rep.inexact = true;
  return r;
}

Rational to_rational(const Interval& x) { return (to_rational(x.inf()) + to_rational(x.sup())) / 2; }

template <> Mpfr round_rational<Mpfr>(const Rational& q, RoundingReport& rep) {
  Mpfr x;  // current default precision
  const int inex = mpfr_set_q(x.backend().data(), q.backend().data(), MPFR_RNDN);
  rep.inexact = rep.inexact || inex != 0;
  return x;
}

Rational to_rational(float x) { return binary_to_rational(x); }
Rational to_rational(double x) { return binary_to_rational(x); }
Rational to_rational(long double x) { return binary_to_rational(x); }

Rational to_rational(const Float128& x) {
  mpfr_t t;
  mpfr_init2(t, 113);
  mpfr_set_float128(t, x.backend().value(), MPFR_RNDN);
  Rational out = mpfr_to_rational(t);
  mpfr_clear(t);
  return out;
}

Rational to_rational(const Mpfr& x) { return mpfr_to_rational(x.backend().data()); }

Rational exact_pow2(long e) {
  const Rational p(boost::multiprecision::mpz_int(1) << static_cast<unsigned>(e < 0 ? -e : e));
  return e >= 0 ? p : Rational(1 / p);
}

long floor_log2(const Rational& x) {
  // 2^e <= x < 2^(e+1): compare bit lengths of numerator and denominator, then adjust.
  const auto n = numerator(x), d = denominator(x);
  long e = static_cast<long>(msb(n)) - static_cast<long>(msb(d));
  Rational p = exact_pow2(e);
  while (p > x) {
    p /= 2;
    --e;
  }
  while (p * 2 <= x) {
    p *= 2;
    ++e;
  }
  return e;
}

}  // namespace qverify
