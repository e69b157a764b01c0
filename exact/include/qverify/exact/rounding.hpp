#pragma once
/// \file rounding.hpp
/// Correctly rounded conversion of an exact Rational to each floating scalar
/// of the ladder (round to nearest, ties to even, gradual underflow), through
/// MPFR with the target format's precision and exponent range. The exact
/// path never calls these; the floating paths round each input exactly once.

#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

namespace qverify {

/// What happened when a value was rounded.
struct RoundingReport {
  bool inexact = false;   ///< the value is not representable: it was rounded
  bool overflow = false;  ///< |value| exceeds the format's largest finite number
  bool underflow = false; ///< a non-zero value rounded to zero or a subnormal
};

template <class S> S round_rational(const Rational& q, RoundingReport& rep);

template <> float round_rational<float>(const Rational& q, RoundingReport& rep);
template <> double round_rational<double>(const Rational& q, RoundingReport& rep);
template <> long double round_rational<long double>(const Rational& q, RoundingReport& rep);
template <> Float128 round_rational<Float128>(const Rational& q, RoundingReport& rep);
/// At the current default precision of Mpfr (see set_mpfr_bits).
template <> Mpfr round_rational<Mpfr>(const Rational& q, RoundingReport& rep);
template <> inline Rational round_rational<Rational>(const Rational& q, RoundingReport&) { return q; }
/// The certified enclosure of q (its bounds rounded outwards).
template <> Interval round_rational<Interval>(const Rational& q, RoundingReport& rep);

/// Exact value of a finite floating number as a Rational (every binary float is
/// a dyadic rational). Used to measure errors of floating results exactly.
Rational to_rational(float x);
Rational to_rational(double x);
Rational to_rational(long double x);
Rational to_rational(const Float128& x);
Rational to_rational(const Mpfr& x);
inline const Rational& to_rational(const Rational& x) { return x; }

/// Exact power-of-two exponent e with 2^e <= x < 2^(e+1) (x > 0).
long floor_log2(const Rational& x);
/// 2^e, exactly.
Rational exact_pow2(long e);

/// Exact rational value of a finite scalar of any precision (an interval: its midpoint).
template <class S> Rational exact_value(const S& x) { return to_rational(x); }

/// Entrywise exact_value.
template <class S, int R, int C> Eigen::Matrix<Rational, R, C> exact_matrix(const Eigen::Matrix<S, R, C>& m) {
  Eigen::Matrix<Rational, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = exact_value(m(i));
  return out;
}

}  // namespace qverify
