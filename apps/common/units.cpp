#include "common/units.h"

#include "common/flags.h"
#include "mcws/core/error.h"

namespace mcws::app {

void declareUnitFlag(CommandLine& cli) {
  cli.addValue("unit", "give lengths, areas and volumes in m, cm or mm (default: the data's unit)");
}

ResultUnits readResultUnits(const CommandLine& cli, std::optional<LengthUnit> data,
                            const std::string& what) {
  if (!cli.has("unit")) return {data, std::nullopt};
  const LengthUnit shown =
      *lengthUnitNamed(parseChoice(cli.required("unit"), "unit", {"m", "cm", "mm"}));
  if (!data) {
    throw Error("--unit " + cli.required("unit") + ": " + what +
                " records no length unit to convert from (a cloud of mcws_sample --shape, or one "
                "written before clouds recorded their robot)");
  }
  return {data, shown};
}

}  // namespace mcws::app
