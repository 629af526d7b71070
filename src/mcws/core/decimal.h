#pragma once
/// \file
/// \brief Strict parsing of a plain decimal number from configuration text, and the text of a
/// number in messages and files (significant digits or fixed decimals).

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mcws {

/// \brief A plain decimal number: an optional sign (when `allow_sign`), digits with at most one
/// point, then an optional exponent. No hexadecimal, "inf", "nan", spaces or trailing text.
/// \return false (value untouched) when the text is not such a finite number.
inline bool parseDecimal(const std::string& text, double& value, bool allow_sign = true) {
  auto digit = [&](std::size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]));
  };
  std::size_t i = 0, digits = 0;
  if (allow_sign && i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
  while (digit(i)) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (digit(i)) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    const std::size_t exponent = i;
    while (digit(i)) ++i;
    if (i == exponent) return false;
  }
  if (i != text.size()) return false;
  const double parsed = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(parsed)) return false;
  value = parsed;
  return true;
}

/// \brief A number to `significant_digits` significant digits without trailing zeros, in fixed or
/// exponent form, whichever printf's "%.Ng" picks: 17 digits read back as the same double
/// (0.10000000000000001), 3 suit a limit in a message (3.4e+38). "nan", "inf", "-inf" as printf.
/// \param significant_digits at least 1 (0 counts as 1, as in printf), at most 17 for a double.
inline std::string formatNumber(double value, int significant_digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", significant_digits, value);
  return text;
}

/// \brief A number for a message: 6 significant digits, no trailing zeros (0.102375, 39, 1e-09,
/// 1e+30), so that a small value never reads as 0.000000 (std::to_string's fixed 6 decimals).
/// The same text as `std::ostream << value` with the stream's default format.
inline std::string formatNumber(double value) { return formatNumber(value, 6); }

/// \brief A number with exactly `decimals` digits after the point ("%.Nf": 2.50, 0.000, 1234.5),
/// for reports whose columns line up; the same text as `std::ostream` with `std::fixed`.
inline std::string formatFixed(double value, int decimals) {
  char text[352];  // "%.Nf" of the largest double has 309 digits before the point
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace mcws
