#pragma once
/// \file number_text.hpp
/// Scene numbers are exact rationals spelled as text: a JSON number literal
/// means the exact decimal it spells (`0.1` is 1/10), a string holds "p/q" or
/// a decimal. This reads the text straight into a Rational, never through a
/// double, and refuses numbers whose exact value would be huge
/// (`1e1000000000`) instead of expanding them.

#include <qverify/exact/scalars.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace qverify {

/// Limits on exact numbers read from text.
struct NumberLimits {
  long max_digits = 10000;          ///< digits in a literal, or in p or q
  long max_decimal_exponent = 10000;  ///< |exponent| of the value, in decimal digits
};

/// Parses a decimal `[-+]d*[.d*][(e|E)[-+]d+]` exactly. On failure returns
/// nullopt and sets `error` to a human-readable reason.
std::optional<Rational> parse_decimal(std::string_view text, std::string& error,
                                      const NumberLimits& limits = {});

/// Parses "p/q" (integers, q != 0) or a decimal, exactly.
std::optional<Rational> parse_rational(std::string_view text, std::string& error,
                                       const NumberLimits& limits = {});

}  // namespace qverify
