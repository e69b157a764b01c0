#pragma once
/// \file precision.hpp
/// The precision ladder of the CLI (`--precision P`) and the dispatch from a
/// run-time precision to a compile-time scalar type.

#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

#include <optional>
#include <string>

namespace qverify {

struct Precision {
  enum class Kind { f32, f64, f80, f128, mpfr, interval, exact };
  Kind kind = Kind::f64;
  unsigned bits = 0;  ///< requested bits for mpfr
  /// The contract's spelling: float, double, long-double, float128, mpfr:BITS, interval, exact.
  std::string name() const;
  /// The bits of a value's significand: 24, 53, 64, 113, MPFR's working precision (at least
  /// `bits`), 53 for an interval (its bounds, and the midpoint a result is read at); nullopt for
  /// exact. Machine epsilon is 2^(1 - bits).
  std::optional<unsigned> significand_bits() const;
};

/// Parses a `--precision` value; nullopt when it is not one of the ladder's.
std::optional<Precision> parse_precision(const std::string& text);

/// Calls f(S{}) with the scalar type of p (for mpfr, after setting the
/// working precision).
template <class F> decltype(auto) with_scalar(const Precision& p, F&& f) {
  switch (p.kind) {
    case Precision::Kind::f32: return f(float{});
    case Precision::Kind::f64: return f(double{});
    case Precision::Kind::f80: return f((long double){});
    case Precision::Kind::f128: return f(Float128{});
    case Precision::Kind::mpfr: set_mpfr_bits(p.bits); return f(Mpfr{});
    case Precision::Kind::exact: return f(Rational{});
    case Precision::Kind::interval: return f(Interval{});
  }
  return f(double{});
}

}  // namespace qverify
