#pragma once
// orocos-kdl as an independent oracle: a KDL chain built straight from a robot file's D-H rows,
// shared by the kinematics tests and the IK benchmark.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cmath>
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <string>

namespace mcws::test {

/// Builds a KDL chain straight from the D-H rows of a robot file, with KDL's own D-H frames, so
/// that it shares no code with mcws's loader: segment 0 is the base; segment i (1..n) is joint i;
/// the last segment is the tool.
inline KDL::Chain kdlChainFromFile(const std::string& path) {
  const YAML::Node root = YAML::LoadFile(path);
  const double angle = root["units"]["angle"].as<std::string>() == "deg" ? M_PI / 180.0 : 1.0;
  auto pose = [&](const YAML::Node& node) {
    if (!node) return KDL::Frame::Identity();
    auto v = [&](const char* key, double scale) {
      return node[key]
                 ? KDL::Vector(node[key][0].as<double>() * scale, node[key][1].as<double>() * scale,
                               node[key][2].as<double>() * scale)
                 : KDL::Vector::Zero();
    };
    const KDL::Vector rpy = v("rpy", angle);
    return KDL::Frame(KDL::Rotation::RPY(rpy.x(), rpy.y(), rpy.z()), v("xyz", 1.0));
  };
  const bool modified = root["convention"].as<std::string>() == "modified";
  const YAML::Node rows = root["joints"];
  auto row = [&](std::size_t i) {
    const YAML::Node r = rows[i];
    const double theta = r["theta"] ? r["theta"].as<double>() * angle : 0.0;
    const double a = r["a"].as<double>(), alpha = r["alpha"].as<double>() * angle;
    const double d = r["d"].as<double>();
    return modified ? KDL::Frame::DH_Craig1989(a, alpha, d, theta)
                    : KDL::Frame::DH(a, alpha, d, theta);
  };
  KDL::Chain chain;
  // Standard D-H: joint motion, then the row's frame. Modified: the row's frame, then the motion,
  // so each row's frame ends the previous segment.
  chain.addSegment(KDL::Segment("base", KDL::Joint(KDL::Joint::None),
                                modified ? pose(root["base"]) * row(0) : pose(root["base"])));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool revolute = rows[i]["type"].as<std::string>() == "revolute";
    const KDL::Joint joint(rows[i]["name"].as<std::string>(),
                           revolute ? KDL::Joint::RotZ : KDL::Joint::TransZ);
    const KDL::Frame tip =
        modified ? (i + 1 < rows.size() ? row(i + 1) : KDL::Frame::Identity()) : row(i);
    chain.addSegment(KDL::Segment(rows[i]["name"].as<std::string>(), joint, tip));
  }
  chain.addSegment(KDL::Segment("tool", KDL::Joint(KDL::Joint::None), pose(root["tool"])));
  return chain;
}

/// A KDL frame as a 4x4 homogeneous matrix.
inline Eigen::Matrix4d toEigen(const KDL::Frame& F) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) M(r, c) = F.M(r, c);
    M(r, 3) = F.p[r];
  }
  return M;
}

}  // namespace mcws::test
