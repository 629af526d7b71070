#pragma once
/// \file
/// \brief The guard around urdfdom: a URDF text is scanned as TinyXML will read it before urdfdom
/// parses it (nesting depth, UTF-8, the XML declaration, no '%' in attributes), urdfdom's messages
/// are caught, and the model it returns is checked to be a tree with printable names. Private to
/// mcws_kinematics (namespace mcws::detail); robot_urdf.cpp reads robots from the guarded model.

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mcws::detail {

/// urdfdom's model of the text, checked to be a tree (checkTreeFreeingLoops()) and to have
/// printable names (checkPrintableNames()).
///
/// urdfdom rejects a URDF in which every link has a parent joint (then the joints necessarily
/// form a loop) as having no root link, without naming a joint. To name the joint that closes the
/// loop, a failed text is parsed again with an extra link that no joint names: if urdfdom then
/// accepts it, that link was the only one without a parent and the tree check finds the loop.
/// \param logged when given, receives every error urdfdom logged, including those of a parse that
///   succeeded (urdfdom skips a `<collision>` or `<visual>` it cannot read and goes on).
/// \throws mcws::Error "source: ...", one line, for what the guards find (checkXmlNesting(),
///   checkTree(), checkPrintableName()) and for text urdfdom rejects ("malformed URDF: " and its
///   first message).
urdf::ModelInterfaceSharedPtr parseUrdfModel(const std::string& text, const std::string& source,
                                             std::vector<std::string>* logged = nullptr);

/// \brief Bounds the recursion of TinyXML over `text` before it parses it (at most
/// kMaxUrdfNesting nested elements, UTF-8, a plain XML declaration, no '%' in attributes); also
/// for the SRDF reader of mcws_collision, which reads its XML with the same TinyXML.
/// \return the offset just after the first top-level `<robot ...>` tag, or npos.
/// \throws mcws::Error "source: ...", one line.
std::size_t checkXmlNesting(const std::string& text, const std::string& source);

/// Message text on one line: line breaks become spaces, trailing spaces are dropped.
std::string oneLine(std::string text);

}  // namespace mcws::detail
