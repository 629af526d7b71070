#pragma once
/// \file
/// \brief The checks and message pieces that every mesh reader of mcws shares (STL and OBJ in
/// mesh_file.cpp, COLLADA in collada_mesh.cpp), so that a bad vertex reads the same whatever the
/// format.

#include <string>
#include <string_view>

namespace mcws {
namespace detail {

/// `word` in single quotes for a message: cut to 32 bytes ("...'" then), control bytes written as
/// \xNN so that a binary file's bytes cannot break the one-line message.
std::string quotedMeshWord(std::string_view word);

/// The number a whole word spells ("1.5", "-2e3", "+4", "nan") into `value`, or false. A word too
/// large for a double gives +-inf (refused by checkMeshCoordinate() as out of range).
bool parseMeshNumber(std::string_view word, double& value);

/// Throws unless a coordinate is finite and at most kLargestMeshCoordinate in size. `where` names
/// it ("'a.obj': line 5: vertex 3: y"), `text` is as the file writes it: "inf" is not a finite
/// number, "1e400" (a finite number too large for a double) is out of range.
/// \throws mcws::Error "<where> coordinate <text> is not a finite number" or "... is out of range
///   (at most 1e9 in size)".
void checkMeshCoordinate(double value, const std::string& where, const std::string& text);

}  // namespace detail
}  // namespace mcws
