#pragma once
/// \file number.hpp
/// A result's numbers as the documents carry them (docs/json-documents.md,
/// "Numbers"), without any document format: the value a scalar of each
/// precision is written as.
///  - float, double: the double itself (a float widens exactly); writers print
///    the shortest text that reads back to it;
///  - long double, float128, mpfr: decimal text with enough digits to read back
///    to the same value in that precision;
///  - exact: "p/q" or "n" in lowest terms;
///  - interval: the enclosure {lo, hi};
///  - a non-finite value: none (its item says why).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

#include <variant>
#include <vector>

namespace qverify {

/// A certified enclosure [lo, hi] of an exact value.
struct Enclosure {
  double lo = 0, hi = 0;
};

/// One number of a result: none (non-finite), a double, decimal or rational text, or an enclosure.
using Number = std::variant<std::monostate, double, std::string, Enclosure>;

Number number_of(float x);
Number number_of(double x);
Number number_of(long double x);
Number number_of(const Float128& x);
Number number_of(const Mpfr& x);
Number number_of(const Rational& x);
Number number_of(const Interval& x);

/// A matrix or a vector of numbers, row-major; a column vector (a plane) has cols == 1.
struct NumberMatrix {
  int rows = 0, cols = 0;
  std::vector<Number> entries;
  const Number& operator()(int i, int j) const { return entries[static_cast<std::size_t>(i * cols + j)]; }
};

template <class Derived> NumberMatrix numbers_of(const Eigen::MatrixBase<Derived>& m) {
  NumberMatrix out{static_cast<int>(m.rows()), static_cast<int>(m.cols()), {}};
  out.entries.reserve(static_cast<std::size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out.entries.push_back(number_of(m(i, j)));
  return out;
}

/// Is every entry finite (always true for exact types)?
template <class Derived> bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  using S = typename Derived::Scalar;
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (!ScalarOps<S>::finite(m(i))) return false;
  return true;
}

}  // namespace qverify
