#pragma once
/// \file
/// \brief What a report of a sampling run (mcws_sample --json) says of its source and its points,
/// each number with its unit.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mcws/io/provenance.h"
#include "mcws/kinematics/robot.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief A validation shape named `name` as JSON: "shape", its exact "area" (planar) or "volume"
/// (shapeMeasure()), "length_unit" (kUnrecordedUnit: a shape has none) and the measure's unit.
nlohmann::json shapeSummary(const std::string& name, Shape shape);

/// \brief Adds the points' bounding box to `summary`: "bbox" {"min", "max"} [x, y, z] and their
/// unit `length_unit` in "units" ("bbox.min", "bbox.max").
void addBoundingBox(nlohmann::json& summary, const SampleSummary& result,
                    const std::string& length_unit);

/// \brief The frame whose origin a result for `robot` is, as reports name it ("tip"): a URDF
/// robot's tip link (Robot::tip_link, whose frame is both its flange and its tool frame), else the
/// D-H robot's "tool" point (its file's `tool:` past the flange) or its "flange", as `point` says.
std::string tipName(const Robot& robot, SamplePoint point = SamplePoint::kTool);

/// \brief Adds what every tool's --json names its robot by: "robot" (Robot::name) and "tip"
/// (tipName()); the tool gives "length_unit" itself.
void addRobotNames(nlohmann::json& out, const Robot& robot, SamplePoint point = SamplePoint::kTool);

/// \brief addRobotNames() for a tool that reads a cloud only: "robot" and "tip" as the cloud's
/// record names them (io::CloudProvenance::robot, io::recordedTip()), each null when the cloud
/// does not record it (a shape's cloud, a PCL cloud, a cloud of an mcws before the record).
void addRecordedRobotNames(nlohmann::json& out, const std::optional<io::CloudProvenance>& recorded);

}  // namespace mcws
