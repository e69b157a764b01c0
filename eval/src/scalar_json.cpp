#include <qverify/exact/precision.hpp>
#include <qverify/eval/scalar_json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

namespace qverify {

nlohmann::ordered_json scalar_json(float x) {
  if (!std::isfinite(x)) return nullptr;
  return static_cast<double>(x);  // exact widening; the shortest double text reads back to x
}
nlohmann::ordered_json scalar_json(double x) {
  if (!std::isfinite(x)) return nullptr;
  return x;  // nlohmann writes the shortest round-trip representation
}
nlohmann::ordered_json scalar_json(long double x) {
  if (!std::isfinite(x)) return nullptr;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*Lg", std::numeric_limits<long double>::max_digits10, x);
  return std::string(buf);
}
nlohmann::ordered_json scalar_json(const Float128& x) {
  if (!boost::multiprecision::isfinite(x)) return nullptr;
  return x.str(std::numeric_limits<Float128>::max_digits10, std::ios_base::fmtflags(0));
}
nlohmann::ordered_json scalar_json(const Mpfr& x) {
  if (!boost::multiprecision::isfinite(x)) return nullptr;
  // p bits round-trip with ceil(p log10 2) + 1 significant digits.
  const auto bits = mpfr_get_prec(x.backend().data());
  const auto digits = static_cast<std::streamsize>(std::ceil(static_cast<double>(bits) * 0.30102999566398120)) + 1;
  return x.str(digits, std::ios_base::fmtflags(0));
}
nlohmann::ordered_json scalar_json(const Rational& x) { return x.str(); }
nlohmann::ordered_json scalar_json(const Interval& x) {
  if (!std::isfinite(x.inf()) || !std::isfinite(x.sup())) return nullptr;
  return {{"lo", x.inf()}, {"hi", x.sup()}};
}

}  // namespace qverify
