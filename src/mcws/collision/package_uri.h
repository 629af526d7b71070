#pragma once
/// \file
/// \brief `package://NAME/path` URIs of robot files resolved as ROS resolves them.

#include <string>
#include <vector>

namespace mcws {

/// \brief Where package:// URIs are looked for.
struct PackageSearch {
  /// Folders given by the user (the tools' --package-path), searched first, in order.
  std::vector<std::string> package_path;
  /// The value of the `ROS_PACKAGE_PATH` variable (folders separated by ':'), searched next;
  /// empty when it is unset. packageSearchFromEnvironment() fills it.
  std::string ros_package_path;
};

/// \brief `package_path` with the `ROS_PACKAGE_PATH` variable of this process.
PackageSearch packageSearchFromEnvironment(std::vector<std::string> package_path);

/// \brief The file that `package://NAME/path` names, for a robot file at `robot_file`.
///
/// Looked for, in order:
/// 1. in each folder of PackageSearch::package_path, then of PackageSearch::ros_package_path: a
///    package folder called NAME holding a `package.xml`, the folder itself or one at any depth
///    below it (as rospack crawls ROS_PACKAGE_PATH: hidden folders and the insides of other
///    packages are not searched, nor deeper than 16 levels);
/// 2. a folder called NAME (with or without `package.xml`) in the robot file's folder or in any
///    folder above it, nearest first (a package checked out next to, or above, its URDF);
/// 3. `package://file.stl` without a folder (as some simulators write): relative to the robot
///    file's folder.
/// The file itself need not exist (the mesh reader says so, naming the path).
/// \param uri a `package://` URI.
/// \throws mcws::Error, one line naming the URI, for a URI without a package name, or a package
///   not found: "mesh 'package://arm/m/a.stl': package 'arm' not found; looked in --package-path
///   /a, /b; ROS_PACKAGE_PATH /opt/ros (or: unset); and for a folder 'arm' in /robots/urdf and
///   each folder above it".
std::string resolvePackageUri(const std::string& uri, const std::string& robot_file,
                              const PackageSearch& search);

}  // namespace mcws
