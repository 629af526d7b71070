#include "mcws/kinematics/robot.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {

std::vector<std::string> jointUnits(const Robot& robot, const std::string& per) {
  std::vector<std::string> units;
  for (const Joint& joint : robot.joints) {
    units.push_back((joint.type == JointType::kRevolute ? "rad" : unitName(robot.length_unit)) +
                    per);
  }
  return units;
}

std::string jointUnitsText(const Robot& robot) {
  const std::vector<std::string> units = jointUnits(robot);
  if (std::all_of(units.begin(), units.end(), [&](const auto& u) { return u == units.front(); }))
    return units.front();
  std::string text;
  for (const std::string& unit : units) text += (text.empty() ? "" : ", ") + unit;
  return text + " (joint by joint)";
}

const char* jointTypeName(JointType type) {
  return type == JointType::kRevolute ? "revolute" : "prismatic";
}

int Robot::jointIndex(const std::string& joint_name) const {
  for (int i = 0; i < dof(); ++i) {
    if (joints[i].name == joint_name) return i;
  }
  std::ostringstream names;
  for (const Joint& joint : joints) names << (names.tellp() > 0 ? ", " : "") << joint.name;
  throw Error("robot '" + name + "' has no joint '" + joint_name + "' (joints: " + names.str() +
              ")");
}

Eigen::VectorXd Robot::lowerLimits() const {
  Eigen::VectorXd limits(dof());
  for (int i = 0; i < dof(); ++i) limits[i] = joints[i].lower;
  return limits;
}

Eigen::VectorXd Robot::upperLimits() const {
  Eigen::VectorXd limits(dof());
  for (int i = 0; i < dof(); ++i) limits[i] = joints[i].upper;
  return limits;
}

void Robot::checkSize(const Eigen::VectorXd& q) const {
  if (q.size() != dof()) {
    throw Error("robot '" + name + "' has " + std::to_string(dof()) + " joints but " +
                std::to_string(q.size()) + " joint values were given");
  }
}

void Robot::checkJointVector(const Eigen::VectorXd& q) const {
  checkSize(q);
  for (int i = 0; i < dof(); ++i) {
    const Joint& joint = joints[i];
    std::ostringstream msg;
    if (!std::isfinite(q[i])) {
      msg << "joint '" << joint.name << "' value " << q[i] << " is not a finite number";
      throw Error(msg.str());
    }
    if (q[i] < joint.lower || q[i] > joint.upper) {
      msg.precision(10);
      msg << "joint '" << joint.name << "' value " << q[i] << " is outside its limits "
          << describeLimits(joint, length_unit);
      throw Error(msg.str());
    }
  }
}

std::string describeLimits(const Joint& joint, LengthUnit unit) {
  const auto limits = [](double lower, double upper) {
    return "[" + formatNumber(lower, 10) + ", " + formatNumber(upper, 10) + "]";
  };
  const std::string text = limits(joint.lower, joint.upper) + " ";
  if (joint.type != JointType::kRevolute) return text + unitName(unit);
  return text + "rad (" + limits(joint.lower * 180.0 / M_PI, joint.upper * 180.0 / M_PI) + " deg)";
}

void checkPrintableName(const std::string& name, const std::string& where) {
  if (hasControlByte(name)) {
    throw Error(where + " name '" + escapedControlBytes(name) +
                "' holds a control byte (names are printable text)");
  }
}

Eigen::Isometry3d dhStandard(double a, double alpha, double d, double theta) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(a, 0.0, d));  // Tz(d) * Tx(a) commute
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  return T;
}

Eigen::Isometry3d dhModified(double a, double alpha, double d, double theta) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  T.translate(Eigen::Vector3d(a, 0.0, 0.0));
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(0.0, 0.0, d));
  return T;
}

Eigen::Isometry3d poseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = xyz;
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

Eigen::Isometry3d poseFromTypedMatrix(const Eigen::Matrix4d& M) {
  if (M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    std::ostringstream msg;
    msg << "last row is "
        << M.row(3).format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, " "))
        << ", not 0 0 0 1";
    throw Error(msg.str());
  }
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double deviation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kTypedRotationTolerance) {
    std::ostringstream msg;
    msg << "the rotation is not orthonormal (|R^T R - I| = " << deviation << ", at most "
        << kTypedRotationTolerance << " accepted)";
    throw Error(msg.str());
  }
  if (R.determinant() < 0.0) {
    throw Error("the rotation is a reflection (det R = " + std::to_string(R.determinant()) + ")");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = svd.matrixU() * svd.matrixV().transpose();
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

void refuseMimicJoints(const Robot& robot, const std::string& what) {
  if (robot.mimic_joints.empty()) return;
  throw Error(robot.source + ": joint '" + robot.mimic_joints.front().joint.name +
              "' mimics another joint of the chain, which " + what +
              " does not support yet (mimic joints off the chain are fine)");
}

double chainLengthScale(const Robot& robot) {
  double reach =
      robot.T_last_flange.translation().norm() + robot.T_flange_tool.translation().norm();
  for (const Joint& joint : robot.joints) {
    reach += joint.T_parent_joint.translation().norm();
    if (joint.type == JointType::kPrismatic) {
      reach += std::max(std::abs(joint.lower), std::abs(joint.upper));
    }
  }
  for (const MimicJoint& mimic : robot.mimic_joints) {
    reach += mimic.joint.T_parent_joint.translation().norm();
    // A prismatic mimic joint's stroke: its master's, times the multiplier, and the offset.
    if (mimic.joint.type == JointType::kPrismatic) {
      const Joint& master = robot.joints[mimic.master];
      reach +=
          std::abs(mimic.offset) +
          std::abs(mimic.multiplier) * std::max(std::abs(master.lower), std::abs(master.upper));
    }
  }
  return reach > 0.0 && std::isfinite(reach) ? reach : 1.0;
}

}  // namespace mcws
