#pragma once
/// \file
/// \brief Strict parsing of a plain decimal number from configuration text, and the short form
/// of a number in messages.

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

/// \brief A number for a message: 6 significant digits, no trailing zeros (0.102375, 39, 1e-09,
/// 1e+30), so that a small value never reads as 0.000000 (std::to_string's fixed 6 decimals).
inline std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace mcws
