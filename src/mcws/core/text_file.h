#pragma once
/// \file
/// \brief The whole text of a configuration file (a robot file, YAML or URDF), with the checks
/// and messages the readers share.

#include <cerrno>
#include <cstring>
#include <fstream>
#include <istream>
#include <sstream>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"

namespace mcws {

/// \brief What is left of an open stream, byte for byte: the reading step of readTextFile(), for
/// readers whose messages are their own. A read that fails part way sets `in.bad()`.
inline std::string readRest(std::istream& in) {
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// \brief Reads a whole text file.
/// \param path the file.
/// \param kind what the file is, for messages ("robot file").
/// \return the file's text.
/// \throws mcws::Error "kind name is empty", "path: kind does not exist", "path: kind is not a
///   regular file" (see requireInputFile()), "path: cannot open kind: reason" or "path: cannot
///   read kind".
inline std::string readTextFile(const std::string& path, const std::string& kind) {
  requireInputFile(path, kind);
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open " + kind + ": " + std::strerror(errno));
  std::string text = readRest(in);
  if (in.bad()) throw Error(path + ": cannot read " + kind);
  return text;
}

}  // namespace mcws
