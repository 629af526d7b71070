#pragma once
/// \file
/// \brief What the region bindings (mcws.boundary, mcws.measure, mcws.envelope) share: positions
/// handed over as float32 (N, 3), as a PCD file holds them, checked as the tools check their
/// input cloud, and the region settings the tools read from --alpha, --correction, --threads.

#include <optional>
#include <string>

#include "bindings.h"
#include "mcws/core/length_unit.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/io/cloud_io.h"
#include "mcws/workspace/measure.h"

namespace mcws::python {

using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// \brief What the messages call the points (a tool names its --input file).
constexpr char kPoints[] = "points";

/// \brief Positions (N, 3) as a cloud. \throws UsageError for another shape.
io::WorkspaceCloud::Ptr cloudOf(const FloatRows& xyz);
/// \brief None: 3-D; else the plane "xy", "xz" or "yz". \throws UsageError naming `plane`.
BoundaryPlane planeOf(const std::optional<std::string>& name);
/// \brief A number as a message shows it (6 significant digits).
std::string number(double value);
/// \brief The cloud checked as mcws_boundary, mcws_measure and mcws_envelope check theirs (enough
/// distinct points, a volume in 3-D, not flat in the plane's axes), and summarised.
CloudSummary checkedRegion(const io::WorkspaceCloud& cloud, BoundaryPlane plane, bool spacing);
/// \brief alpha [local spacings] (default 3, 5 with correction "none"), correction ("efron" or
/// "none") and threads, checked as the tools' --alpha, --correction and --threads.
MeasureOptions regionOptions(const std::optional<double>& alpha, const std::string& correction,
                             int threads);
/// \brief The units of a result whose positions are in `length_unit` ("m", "cm", "mm"; none:
/// "unrecorded"). \throws UsageError for another name.
ResultUnits resultUnits(const std::optional<std::string>& length_unit);

/// \brief `call()`, a library mcws::Error it throws prefixed with "points: " (as a tool names its
/// input file); usage errors pass unchanged.
template <typename Call>
auto namingPoints(Call&& call) -> decltype(call()) {
  try {
    return call();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw Error(std::string(kPoints) + ": " + e.what());
  }
}

}  // namespace mcws::python
