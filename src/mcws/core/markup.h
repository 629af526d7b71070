#pragma once
/// \file
/// \brief Text written into XML or HTML.

#include <string>

namespace mcws {

/// \brief `text` escaped for XML and HTML element content and double-quoted attribute values:
/// & < > " written as entities.
inline std::string escapeMarkup(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace mcws
