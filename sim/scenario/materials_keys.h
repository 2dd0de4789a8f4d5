#pragma once
// The [materials] section's key table (base/key_table.h): every property of the ice and the water
// once, with its unit, default, doc line and supported range. The scenario parser, the rules
// (scenario_rules.cpp), summary.json, the GUI's Scenario tab and docs/simulate.md read it
// (tests/sim/scenario/test_materials_keys.cpp holds the page to the table). Knows nothing of TOML.
#include <span>
#include <string_view>

#include "base/key_table.h"
#include "sim/scenario/scenario.h"

namespace thaw::sim {

/// The [materials] table's own columns: the supported range of a property (the rules reject a
/// value outside it) and the range typical scenarios use (only for naming the likely cause when
/// the solver fails). `flow`: a key only the flowing water reads ([simulation] flow), whose rules
/// are its own (scenario_file.cpp) and which summary.json writes only with flow.
struct MaterialsColumns {
  double lo = 0, hi = 0;                  ///< supported, inclusive
  double typical_lo = 0, typical_hi = 0;  ///< what shipped scenarios and the literature use
  bool decades = true;        ///< distance from typical in decades (else in units of 100 K)
  std::string_view why = {};  ///< why the supported range
  bool flow = false;
};

using MaterialsKey = KeyRow<Materials, MaterialsColumns>;

/// Every [materials] key: the properties in the order of data/materials/ice_water.toml, then the
/// flowing water's keys.
std::span<const MaterialsKey> materials_keys();

}  // namespace thaw::sim
