#include <qverify/verify/precision.hpp>
#include <qverify/verify/scalar_json.hpp>

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

std::string Precision::name() const {
  switch (kind) {
    case Kind::f32: return "float";
    case Kind::f64: return "double";
    case Kind::f80: return "long-double";
    case Kind::f128: return "float128";
    case Kind::mpfr: return "mpfr:" + std::to_string(bits);
    case Kind::interval: return "interval";
    case Kind::exact: return "exact";
  }
  return "?";
}

std::optional<Precision> parse_precision(const std::string& t) {
  Precision p;
  if (t == "float") p.kind = Precision::Kind::f32;
  else if (t == "double") p.kind = Precision::Kind::f64;
  else if (t == "long-double") p.kind = Precision::Kind::f80;
  else if (t == "float128") p.kind = Precision::Kind::f128;
  else if (t == "interval") p.kind = Precision::Kind::interval;
  else if (t == "exact") p.kind = Precision::Kind::exact;
  else if (t.rfind("mpfr:", 0) == 0) {
    const std::string b = t.substr(5);
    if (b.empty() || b.size() > 6 || b.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    const unsigned long bits = std::stoul(b);
    if (bits < 16 || bits > 65536) return std::nullopt;
    p.kind = Precision::Kind::mpfr;
    p.bits = static_cast<unsigned>(bits);
  } else return std::nullopt;
  return p;
}

}  // namespace qverify
