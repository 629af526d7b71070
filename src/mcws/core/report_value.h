#pragma once
/// \file
/// \brief A number of a result with its name and unit, so that a report lists each once: the
/// tools put `value` under `name` in their JSON and `unit` under the same name in its "units" map.

#include <string>

namespace mcws {

/// \brief One number of a result, e.g. {"volume", 1.2, "m^3"}.
struct ReportValue {
  std::string name;
  double value{0.0};
  std::string unit;
};

}  // namespace mcws
