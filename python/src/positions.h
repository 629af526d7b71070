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
#include "mcws/io/provenance.h"
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
/// \brief io::requireVolume(cloud, name) with `hint` for its "give --plane" (a tool's flag, which
/// the Python functions do not have).
template <typename Cloud>
void requireVolumeHinted(const Cloud& cloud, const std::string& name, const std::string& hint) {
  try {
    io::requireVolume(cloud, name);
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    std::string text = e.what();
    const std::string flag = "give --plane";
    const std::size_t at = text.rfind(flag);
    if (at != std::string::npos) text.replace(at, flag.size(), hint);
    throw Error(text);
  }
}

/// \brief The cloud checked as mcws_boundary, mcws_measure and mcws_envelope check theirs (enough
/// distinct points, a volume in 3-D, not flat in the plane's axes), and summarised; a flat 3-D
/// cloud's message ends with `flat_hint`.
CloudSummary checkedRegion(const io::WorkspaceCloud& cloud, BoundaryPlane plane, bool spacing,
                           const std::string& flat_hint = "give plane");
/// \brief alpha [local spacings] (default 3, 5 with correction "none"), correction ("efron" or
/// "none") and threads, checked as the tools' --alpha, --correction and --threads.
MeasureOptions regionOptions(const std::optional<double>& alpha, const std::string& correction,
                             int threads);
/// \brief The units of a result whose positions are in `length_unit` ("m", "cm", "mm"), else in the
/// unit `recorded` names, else "unrecorded". \throws UsageError for another name, or one that is
/// not the recorded unit.
ResultUnits resultUnits(const std::optional<std::string>& length_unit,
                        const std::optional<io::CloudProvenance>& recorded = std::nullopt);

struct LoadedRobot;

/// \brief What a cloud file's header would record of the points of mcws.measure and mcws.envelope
/// (an array records nothing): `provenance`, a dict as read_provenance() returns, checked as
/// write_pcd() checks it; or for `robot` (an mcws.Robot) the record mcws_sample writes of a cloud
/// sampled at its tool point (robot name, file, chain, point "tool"); none without either. The
/// results name "robot" and "tip" from it, as the tools name them from their input's header.
/// \throws UsageError for a malformed provenance.
std::optional<io::CloudProvenance> pointsRecord(const LoadedRobot* robot,
                                                const py::object& provenance);

/// \brief The provenance a dict of read_provenance()'s keys records, checked as a header line is.
/// \throws UsageError "provenance: ..." naming what is wrong.
io::CloudProvenance provenanceFromDict(const py::dict& dict);

/// \brief The sampling record a dict of read_provenance()["sampling"]'s keys (point, collision,
/// fix) gives; with `defaults` a key left out takes sample()'s default (point "tool", no
/// collision labels, no joint fixed). \throws Error "where.key: ..." naming the key and the value
/// of a wrong type, a missing key (without `defaults`) or an unknown one.
io::SamplingRecord samplingFromDict(const py::handle& value, const std::string& where,
                                    bool defaults);

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
