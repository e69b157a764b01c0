#include <qverify/exact/precision.hpp>

#include <string>

namespace qverify {

std::optional<unsigned> Precision::significand_bits() const {
  switch (kind) {
    case Kind::f32: return 24;
    case Kind::f64:
    case Kind::interval: return 53;
    case Kind::f80: return 64;
    case Kind::f128: return 113;
    case Kind::mpfr: return digits_for_bits(bits).bits;
    case Kind::exact: return std::nullopt;
  }
  return std::nullopt;
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
