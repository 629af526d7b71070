#pragma once
/// \file
/// \brief --unit m|cm|mm: the unit a tool gives its lengths, areas and volumes in (the classes
/// and the JSON convention are in mcws/core/length_unit.h).

#include <optional>
#include <string>

#include "common/app.h"
#include "mcws/core/length_unit.h"

namespace mcws::app {

/// \brief Declares --unit (read by readResultUnits()).
void declareUnitFlag(CommandLine& cli);

/// \brief The units of a tool's results: `data` and --unit if given.
/// \param what names the input in the message when --unit is given but `data` is none.
/// \throws UsageError for a --unit other than m, cm, mm; Error for a --unit with data that records
///   no unit ("--unit m: ball.pcd records no length unit to convert from").
ResultUnits readResultUnits(const CommandLine& cli, std::optional<LengthUnit> data,
                            const std::string& what);

}  // namespace mcws::app
