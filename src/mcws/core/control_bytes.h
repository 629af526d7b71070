#pragma once
/// \file
/// \brief Control bytes in names and messages: whether text holds one, and the \xNN form that
/// keeps a message on one line whatever bytes a file held.

#include <algorithm>
#include <cstdio>
#include <string>
#include <string_view>

namespace mcws {

/// \brief Whether `byte` is a control byte: below 0x20 (tab and line breaks included), or 0x7f.
/// Bytes from 0x80 up are not (UTF-8 text).
inline bool isControlByte(unsigned char byte) { return byte < 0x20 || byte == 0x7f; }

/// \brief `byte` as a message shows it: a backslash, 'x' and two lowercase hexadecimal digits
/// ("\x0a", "\x7f", "\xff").
inline std::string escapedByte(unsigned char byte) {
  char text[5];
  std::snprintf(text, sizeof text, "\\x%02x", byte);
  return text;
}

/// \brief Whether `text` holds a control byte (isControlByte()). A robot, joint or link name
/// must not: it would break the one-line messages of the tools and the headers of the files they
/// write, which every later tool then refuses.
inline bool hasControlByte(std::string_view text) {
  return std::any_of(text.begin(), text.end(),
                     [](char c) { return isControlByte(static_cast<unsigned char>(c)); });
}

/// \brief `text` with its control bytes written as \xNN ("arm\x0a2"), every other byte kept.
inline std::string escapedControlBytes(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    out += isControlByte(byte) ? escapedByte(byte) : std::string(1, c);
  }
  return out;
}

}  // namespace mcws
