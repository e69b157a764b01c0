#pragma once
/// \file mpfi.hpp
/// Certified intervals of arbitrary precision: Boost.Multiprecision's
/// `mpfi_float` (MPFI, Debian `libmpfi-dev`) without expression templates.
///
/// Every operation returns an interval [lo, hi] (MPFR bounds, outward
/// rounding) that contains the exact result, so a computation started from
/// enclosures of exact inputs encloses the exact result at any precision.
/// Like `Interval` (interval.hpp), decisions go through ScalarOps: a
/// comparison holds only when it is certain, and nothing throws. Used where
/// `Interval`'s 53 bits cannot decide a sign: the certified re-trace of
/// disagreeing pixels (render/) and the MPFR stage of the adaptive ladder.

#include <qverify/core/scalar.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/scalars.hpp>

#include <boost/multiprecision/mpfi.hpp>

namespace qverify {

using Mpfi = boost::multiprecision::number<boost::multiprecision::mpfi_float_backend<0>, boost::multiprecision::et_off>;

/// Sets the precision (bits of each bound) of newly created `Mpfi` values to
/// at least `bits`, returns the precision used (see set_mpfr_bits).
inline unsigned set_mpfi_bits(unsigned bits) {
  const DigitsForBits p = digits_for_bits(bits);
  Mpfi::default_precision(p.digits10);
  return p.bits;
}

/// The tightest enclosure of q at the current Mpfi precision (exact when q is
/// representable).
inline Mpfi enclose_mpfi(const Rational& q) {
  Mpfi r;
  mpfi_set_q(r.backend().data(), q.backend().data());
  return r;
}

/// Inputs of a typed scene in Mpfi: their enclosure (inexact when not a point).
template <> inline Mpfi round_rational<Mpfi>(const Rational& q, RoundingReport& rep) {
  Mpfi r = enclose_mpfi(q);
  if (!mpfi_bounded_p(r.backend().data())) rep.overflow = true;
  else if (!mpfr_equal_p(&r.backend().data()->left, &r.backend().data()->right)) rep.inexact = true;
  return r;
}

/// The lower and upper bound, exactly (at the interval's own precision).
inline Mpfr mpfi_lower(const Mpfi& x) {
  Mpfr r;
  mpfr_set_prec(r.backend().data(), mpfi_get_prec(x.backend().data()));
  mpfi_get_left(r.backend().data(), x.backend().data());
  return r;
}
inline Mpfr mpfi_upper(const Mpfi& x) {
  Mpfr r;
  mpfr_set_prec(r.backend().data(), mpfi_get_prec(x.backend().data()));
  mpfi_get_right(r.backend().data(), x.backend().data());
  return r;
}

}  // namespace qverify

template <> struct qverify::ScalarOps<qverify::Mpfi> {
  using S = qverify::Mpfi;
  static constexpr bool interval = true;
  static bool exact() { return false; }
  static bool less(const S& a, const S& b) {
    return mpfr_less_p(qverify::mpfi_upper(a).backend().data(), qverify::mpfi_lower(b).backend().data()) != 0;
  }
  static bool is_zero(const S& a) { return mpfi_is_zero(a.backend().data()) > 0; }
  static S abs(const S& x) { return boost::multiprecision::abs(x); }
  static bool finite(const S& x) { return mpfi_bounded_p(x.backend().data()) != 0; }
};
