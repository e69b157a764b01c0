#pragma once
/// \file scalar_json.hpp
/// Number encoding of the CLI contract (cli.md, "Number encoding in output"):
///  float, double: JSON numbers that round-trip exactly;
///  long double, float128, mpfr: decimal strings with enough digits to
///  round-trip in that precision; exact: "p/q" or "n" in lowest terms.
/// A non-finite value is written as null (its item says why).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

#include <nlohmann/json.hpp>

namespace qverify {

nlohmann::ordered_json scalar_json(float x);
nlohmann::ordered_json scalar_json(double x);
nlohmann::ordered_json scalar_json(long double x);
nlohmann::ordered_json scalar_json(const Float128& x);
nlohmann::ordered_json scalar_json(const Mpfr& x);
nlohmann::ordered_json scalar_json(const Rational& x);
/// {"lo": number, "hi": number}: a certified enclosure.
nlohmann::ordered_json scalar_json(const Interval& x);

template <class Derived> nlohmann::ordered_json matrix_json(const Eigen::MatrixBase<Derived>& m) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  if (m.cols() == 1) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) out.push_back(scalar_json(m(i)));
    return out;
  }
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(scalar_json(m(i, j)));
    out.push_back(std::move(row));
  }
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
