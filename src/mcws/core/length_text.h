#pragma once
/// \file
/// \brief Numbers and lengths written as text, as the tools' flags and the Python module's
/// arguments take them ("0.05", "2cm", "0.02m"), with the one-line messages both give.

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/length_unit.h"

namespace mcws {

/// \brief A finite number in decimal notation (digits, sign, point, exponent: no hex, "inf",
/// "nan" or blanks, which strtod alone would take).
/// \param name what the messages call the text: a flag ("--radius") or an argument ("radius").
/// \throws UsageError "name: 'text' is not a finite number".
inline double decimalFromText(const std::string& text, const std::string& name) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const bool decimal =
      !text.empty() && text.find_first_not_of("0123456789+-.eE") == std::string::npos;
  const double value = decimal ? std::strtod(begin, &end) : 0.0;
  if (!decimal || end != begin + text.size() || errno == ERANGE || !std::isfinite(value)) {
    throw UsageError(name + ": '" + text + "' is not a finite number");
  }
  return value;
}

/// \brief A length: a number with an optional unit suffix, without a blank (m, cm, mm: "2cm",
/// "0.02m"), converted to `unit`; a bare number is already in `unit`.
/// \param name what the messages call the text: a flag ("--resolution") or an argument.
/// \param allow_zero accept 0 (a distance that may be none) as well as positive lengths.
/// \returns [unit]
/// \throws UsageError "name: 'text' is not a finite number" (the text without its unit),
///   "name: N is not a positive number" (or "is less than 0" with allow_zero) or
///   "name: text is too large".
inline double lengthFromText(const std::string& text, const std::string& name, LengthUnit unit,
                             bool allow_zero = false) {
  std::size_t end = text.size();
  double scale = 1.0;
  for (const auto& [suffix, metres] : {std::pair{"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}}) {
    const std::string s = suffix;
    if (text.size() > s.size() && text.compare(text.size() - s.size(), s.size(), s) == 0) {
      end = text.size() - s.size();
      scale = metres / unitInMetres(unit);
      break;
    }
  }
  const std::string number = text.substr(0, end);
  const double value = decimalFromText(number, name);
  if (allow_zero && value < 0.0) throw UsageError(name + ": " + number + " is less than 0");
  if (!allow_zero && !(value > 0.0)) {
    throw UsageError(name + ": " + number + " is not a positive number");
  }
  if (!std::isfinite(value * scale)) throw UsageError(name + ": " + text + " is too large");
  return value * scale;
}

}  // namespace mcws
