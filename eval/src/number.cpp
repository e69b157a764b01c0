#include <qverify/exact/precision.hpp>
#include <qverify/eval/number.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

namespace qverify {

Number number_of(float x) {
  if (!std::isfinite(x)) return {};
  return static_cast<double>(x);  // exact widening; the shortest double text reads back to x
}
Number number_of(double x) {
  if (!std::isfinite(x)) return {};
  return x;
}
Number number_of(long double x) {
  if (!std::isfinite(x)) return {};
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*Lg", std::numeric_limits<long double>::max_digits10, x);
  return std::string(buf);
}
Number number_of(const Float128& x) {
  if (!boost::multiprecision::isfinite(x)) return {};
  return x.str(std::numeric_limits<Float128>::max_digits10, std::ios_base::fmtflags(0));
}
Number number_of(const Mpfr& x) {
  if (!boost::multiprecision::isfinite(x)) return {};
  // p bits round-trip with ceil(p log10 2) + 1 significant digits.
  const auto bits = mpfr_get_prec(x.backend().data());
  const auto digits = static_cast<std::streamsize>(std::ceil(static_cast<double>(bits) * 0.30102999566398120)) + 1;
  return x.str(digits, std::ios_base::fmtflags(0));
}
Number number_of(const Rational& x) { return x.str(); }
Number number_of(const Interval& x) {
  if (!std::isfinite(x.inf()) || !std::isfinite(x.sup())) return {};
  return Enclosure{x.inf(), x.sup()};
}

}  // namespace qverify
