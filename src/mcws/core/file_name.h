#pragma once
/// \file
/// \brief File-name helpers shared by the readers and writers that pick a format by extension.

#include <filesystem>
#include <string>

namespace mcws {

/// \brief The extension of `path` with its dot, in lower case (".stl" for "Arm.STL"; "" for none).
inline std::string lowercaseExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return extension;
}

}  // namespace mcws
