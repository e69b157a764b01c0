#pragma once
/// \file scalars.hpp
/// The scalar types of the precision ladder and their Eigen::NumTraits.
///
///  - `Rational`: GMP rationals through Boost.Multiprecision with expression
///    templates *off* (Eigen's fixed-size kernels do not compile with
///    Boost's expression templates: they hand Eigen expression objects where
///    it expects the scalar type). Exact: NumTraits
///    epsilon is 0, so every tolerance of the core collapses to an equality.
///  - `Float128`: IEEE binary128 (libquadmath).
///  - `Mpfr`: MPFR with run-time precision (`Mpfr::default_precision(bits)`
///    in digits10, or `set_mpfr_bits`).
/// The choice of Rational over CGAL::Gmpq and cpp_rational is measured by
/// `bench/bench_scalars` (README, "Exact arithmetic: which rational type").

#include <boost/multiprecision/float128.hpp>
#include <boost/multiprecision/gmp.hpp>
#include <boost/multiprecision/mpfr.hpp>

#include <Eigen/Core>
#include <limits>
#include <type_traits>

namespace qverify {

using Rational = boost::multiprecision::number<boost::multiprecision::gmp_rational, boost::multiprecision::et_off>;
using Float128 = boost::multiprecision::float128;
using Mpfr = boost::multiprecision::number<boost::multiprecision::mpfr_float_backend<0>, boost::multiprecision::et_off>;

/// Sets the working precision of newly created `Mpfr` values to at least
/// `bits` bits and returns the precision actually used. Boost 1.74 sets MPFR
/// precision in decimal digits (d10 -> digits10_2_2(d10) bits), so the working
/// precision is the smallest such value >= bits; reports state it.
/// The smallest Boost precision in decimal digits whose binary precision is at
/// least `bits`, and that binary precision (shared by Mpfr and Mpfi).
struct DigitsForBits {
  unsigned digits10, bits;
};
inline DigitsForBits digits_for_bits(unsigned bits) {
  unsigned d10 = 1;
  while (boost::multiprecision::detail::digits10_2_2(d10) < bits) ++d10;
  return {d10, static_cast<unsigned>(boost::multiprecision::detail::digits10_2_2(d10))};
}

inline unsigned set_mpfr_bits(unsigned bits) {
  const DigitsForBits p = digits_for_bits(bits);
  Mpfr::default_precision(p.digits10);
  return p.bits;
}

/// Human-readable name of a scalar type of the ladder.
template <class S> const char* scalar_name() {
  if constexpr (std::is_same_v<S, float>) return "float";
  else if constexpr (std::is_same_v<S, double>) return "double";
  else if constexpr (std::is_same_v<S, long double>) return "long double";
  else if constexpr (std::is_same_v<S, Float128>) return "float128";
  else if constexpr (std::is_same_v<S, Mpfr>) return "mpfr";
  else if constexpr (std::is_same_v<S, Rational>) return "exact rationals";
  else return "this precision";
}

/// Bits of precision of a newly created Mpfr value.
inline unsigned mpfr_working_bits() {
  Mpfr probe;
  return static_cast<unsigned>(mpfr_get_prec(probe.backend().data()));
}

/// Eigen::NumTraits of an exact scalar S (WideInt, DigitPack, the symbolic Poly): epsilon 0, so
/// that every tolerance of the core is an equality (ScalarOps' exact()), and the costs Eigen's
/// expression evaluation weighs.
template <class S, int IsInt, int Add, int Mul> struct ExactNumTraits : Eigen::GenericNumTraits<S> {
  using Real = S;
  using NonInteger = S;
  using Literal = S;
  using Nested = S;
  enum { IsComplex = 0, IsInteger = IsInt, IsSigned = 1, RequireInitialization = 1, ReadCost = 1, AddCost = Add, MulCost = Mul };
  static Real epsilon() { return Real(0); }
  static Real dummy_precision() { return Real(0); }
  static Real highest() { return Real(0); }
  static Real lowest() { return Real(0); }
  static int digits10() { return 0; }
};

}  // namespace qverify

namespace Eigen {

/// NumTraits for Boost.Multiprecision numbers without expression templates.
/// Rationals are exact: epsilon() == dummy_precision() == 0.
template <class Backend>
struct NumTraits<boost::multiprecision::number<Backend, boost::multiprecision::et_off>>
    : GenericNumTraits<boost::multiprecision::number<Backend, boost::multiprecision::et_off>> {
  using Self = boost::multiprecision::number<Backend, boost::multiprecision::et_off>;
  using Real = Self;
  using NonInteger = Self;
  using Literal = Self;
  using Nested = Self;
  static constexpr bool exact =
      boost::multiprecision::number_category<Self>::value == boost::multiprecision::number_kind_rational;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 20,
    MulCost = 40
  };
  static Real epsilon() {
    if constexpr (exact) return Real(0);
    else return std::numeric_limits<Self>::epsilon();
  }
  static Real dummy_precision() {
    if constexpr (exact) return Real(0);
    else return Real(1000) * epsilon();
  }
  static Real highest() {
    if constexpr (exact) return Real(0);
    else return (std::numeric_limits<Self>::max)();
  }
  static Real lowest() {
    if constexpr (exact) return Real(0);
    else return -(std::numeric_limits<Self>::max)();
  }
  static int digits10() {
    if constexpr (exact) return 0;
    else return std::numeric_limits<Self>::digits10;
  }
};

}  // namespace Eigen
