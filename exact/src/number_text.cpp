#include <qverify/exact/number_text.hpp>

#include <cctype>

namespace qverify {
namespace {

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

/// 10^n as a GMP integer (n >= 0).
Rational pow10(long n) {
  mpz_t z;
  mpz_init(z);
  mpz_ui_pow_ui(z, 10, static_cast<unsigned long>(n));
  Rational r{boost::multiprecision::mpz_int(z)};
  mpz_clear(z);
  return r;
}

std::optional<Rational> parse_integer(std::string_view s, std::string& error, const NumberLimits& limits) {
  bool neg = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  if (!all_digits(s)) {
    error = "not an integer";
    return std::nullopt;
  }
  // Leading zeros are decimal here: GMP would read "010" as octal (and throw on "09").
  while (s.size() > 1 && s[0] == '0') s.remove_prefix(1);
  if (static_cast<long>(s.size()) > limits.max_digits) {
    error = "integer has " + std::to_string(s.size()) + " digits (limit " + std::to_string(limits.max_digits) + ")";
    return std::nullopt;
  }
  Rational r{boost::multiprecision::mpz_int(std::string(s))};
  return neg ? Rational(-r) : r;
}

}  // namespace

std::optional<Rational> parse_decimal(std::string_view text, std::string& error, const NumberLimits& limits) {
  std::string_view s = text;
  bool neg = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    neg = s[0] == '-';
    s.remove_prefix(1);
  }
  const auto epos = s.find_first_of("eE");
  std::string_view mant = s.substr(0, epos);
  std::string_view expo = epos == std::string_view::npos ? std::string_view{} : s.substr(epos + 1);
  const auto dot = mant.find('.');
  std::string_view ip = mant.substr(0, dot);
  std::string_view fp = dot == std::string_view::npos ? std::string_view{} : mant.substr(dot + 1);
  if ((ip.empty() && fp.empty()) || (!ip.empty() && !all_digits(ip)) || (!fp.empty() && !all_digits(fp)) ||
      (dot != std::string_view::npos && ip.empty() && fp.empty())) {
    error = "not a number: \"" + std::string(text.substr(0, 40)) + "\"";
    return std::nullopt;
  }
  long e = 0;
  if (epos != std::string_view::npos) {
    bool eneg = false;
    if (!expo.empty() && (expo[0] == '-' || expo[0] == '+')) {
      eneg = expo[0] == '-';
      expo.remove_prefix(1);
    }
    if (!all_digits(expo)) {
      error = "bad exponent in \"" + std::string(text.substr(0, 40)) + "\"";
      return std::nullopt;
    }
    // Refuse huge exponents before converting them.
    std::string_view ed = expo;
    while (ed.size() > 1 && ed[0] == '0') ed.remove_prefix(1);
    if (ed.size() > 9) {
      error = "exponent too large in \"" + std::string(text.substr(0, 40)) + "\" (limit 1e" +
              std::to_string(limits.max_decimal_exponent) + ")";
      return std::nullopt;
    }
    e = std::stol(std::string(ed));
    if (eneg) e = -e;
  }
  std::string digits = std::string(ip) + std::string(fp);
  const auto nz = digits.find_first_not_of('0');
  if (nz == std::string::npos) return Rational(0);
  digits.erase(0, nz);
  if (static_cast<long>(digits.size()) > limits.max_digits) {
    error = "number has " + std::to_string(digits.size()) + " significant digits (limit " +
            std::to_string(limits.max_digits) + ")";
    return std::nullopt;
  }
  const long scale = e - static_cast<long>(fp.size());  // value = digits * 10^scale
  // the leading digit's decimal exponent (floor(log10 |x|)): 1e10000 and 1e-10000 are in, 1e-10001 is not
  const long leading = scale + static_cast<long>(digits.size()) - 1;
  if (leading > limits.max_decimal_exponent || leading < -limits.max_decimal_exponent) {
    error = "number \"" + std::string(text.substr(0, 40)) + "\" is out of the exact range (|exponent| <= " +
            std::to_string(limits.max_decimal_exponent) + ")";
    return std::nullopt;
  }
  Rational r{boost::multiprecision::mpz_int(digits)};
  if (scale > 0) r *= pow10(scale);
  if (scale < 0) r /= pow10(-scale);
  return neg ? Rational(-r) : r;
}

std::optional<Rational> parse_rational(std::string_view text, std::string& error, const NumberLimits& limits) {
  const auto slash = text.find('/');
  if (slash == std::string_view::npos) return parse_decimal(text, error, limits);
  auto p = parse_integer(text.substr(0, slash), error, limits);
  if (!p) {
    error = "numerator of \"" + std::string(text.substr(0, 40)) + "\": " + error;
    return std::nullopt;
  }
  std::string_view qs = text.substr(slash + 1);
  if (!qs.empty() && (qs[0] == '-' || qs[0] == '+')) {
    error = "denominator of \"" + std::string(text.substr(0, 40)) + "\" must be an unsigned integer";
    return std::nullopt;
  }
  auto q = parse_integer(qs, error, limits);
  if (!q) {
    error = "denominator of \"" + std::string(text.substr(0, 40)) + "\": " + error;
    return std::nullopt;
  }
  if (*q == 0) {
    error = "zero denominator in \"" + std::string(text.substr(0, 40)) + "\"";
    return std::nullopt;
  }
  return Rational(*p / *q);
}

}  // namespace qverify
