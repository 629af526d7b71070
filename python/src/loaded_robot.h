#pragma once
/// \file
/// \brief The object behind mcws.Robot: the robot and the file and chain it was read from, which
/// the collision model and a cloud's provenance need again.

#include <memory>
#include <string>
#include <vector>

#include "mcws/kinematics/robot.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {
class CollisionChecker;
}

namespace mcws::python {

/// \brief A robot read from a file (mcws.Robot).
struct LoadedRobot {
  Robot robot;
  std::string path;        ///< the file, as given
  UrdfChainOptions chain;  ///< the URDF chain asked for (base, tip); empty: the whole tree's
};

/// \brief The robot of a `.yaml` or `.urdf` file; `base` and `tip` (links, URDF only) pick a chain,
/// `package_path` (folders, URDF only) and `srdf` (a file, or "") are kept on the robot for its
/// collision model, as the tools' --package-path and --srdf.
/// \throws mcws::Error naming the file (the library's message); UsageError for base, tip or
///   package_path with a robot that is not a `.urdf`, a package_path that is not a folder, an srdf
///   that is not a file.
LoadedRobot loadRobotFile(const std::string& path, const std::string& base, const std::string& tip,
                          const std::vector<std::string>& package_path = {},
                          const std::string& srdf = "");

/// \brief The collision checker of the robot's collision model, as mcws_sample --collision
/// builds it. \throws mcws::Error "<path>: has no collision geometry ..." when the file has none.
std::unique_ptr<CollisionChecker> collisionChecker(const LoadedRobot& loaded);

/// \brief The collision checker of the robot's collision model, or nullptr when the file has no
/// collision geometry (as the reach tools' checker of a study); `environment` false: the links
/// and the tool only (a map meant for other base positions).
std::unique_ptr<CollisionChecker> collisionCheckerIfModelled(const LoadedRobot& loaded,
                                                             bool environment);

}  // namespace mcws::python
