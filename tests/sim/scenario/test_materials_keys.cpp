// The [materials] key table (sim/scenario/materials_keys.h) against what reads it: the built-in
// material file sets every property row to the default the row documents, the schema accepts
// exactly the rows' keys, summary.json writes the properties' rows, the rules check each row's
// range, and docs/simulate.md's [materials] rows are the table's, row for row.
#include "sim/scenario/materials_keys.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "base/error.h"
#include "base/number_text.h"
#include "sim/format/scenario_file.h"
#include "sim/scenario/scenario_rules.h"

namespace thaw::sim {
namespace {

double value_of(const MaterialsKey& row, const Materials& m) {
  return m.*(std::get<NumberKey<Materials>>(row.value).field);
}

TEST(MaterialsKeys, NamesAreUniqueAndPropertiesAreNumbersWithARange) {
  std::set<std::string_view> names;
  for (const MaterialsKey& row : materials_keys()) {
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    EXPECT_EQ(find_key(materials_keys(), row.name), &row);
    if (row.extra.flow) continue;
    EXPECT_TRUE(std::holds_alternative<NumberKey<Materials>>(row.value)) << row.name;
    EXPECT_LT(row.extra.lo, row.extra.hi) << row.name;
    EXPECT_LE(row.extra.lo, row.extra.typical_lo) << row.name;
    EXPECT_LE(row.extra.typical_hi, row.extra.hi) << row.name;
  }
}

TEST(MaterialsKeys, BuiltInMaterialsAreTheDocumentedDefaultsInsideTheirRanges) {
  const Materials m = default_materials();
  for (const MaterialsKey& row : materials_keys()) {
    if (row.extra.flow) continue;
    const double v = value_of(row, m);
    EXPECT_EQ(shortest_text(v), row.default_text) << row.name;
    EXPECT_EQ(v, value_of(row, Materials{})) << row.name << ": Materials{} and the data file";
    EXPECT_GE(v, row.extra.lo) << row.name;
    EXPECT_LE(v, row.extra.hi) << row.name;
  }
}

TEST(MaterialsKeys, SummaryWritesEveryPropertyRow) {
  const nlohmann::json j = scenario_to_json(default_scenario());
  std::set<std::string> expected;
  for (const MaterialsKey& row : materials_keys())
    if (!row.extra.flow) expected.emplace(row.name);
  std::set<std::string> written;
  for (const auto& [key, value] : j.at("materials").items()) written.insert(key);
  EXPECT_EQ(written, expected);
}

TEST(MaterialsKeys, EveryRowIsAKeyOfTheFileAndTheRulesCheckEachPropertysRange) {
  for (const MaterialsKey& row : materials_keys()) {
    if (row.extra.flow) continue;
    const std::string key(row.name);
    const Scenario read = parse_scenario_string(
        default_scenario_text() + "\n[materials]\n" + key + " = " + row.default_text.data() + "\n",
        "s.toml");
    EXPECT_EQ(value_of(row, read.materials), value_of(row, default_materials())) << key;
    // A melting point outside its range puts the initial temperatures on the wrong side of it:
    // the temperature rules, checked first, name those keys.
    if (row.name == "melting_point_c") continue;
    const double outside = row.extra.hi * 10 + 1000;
    try {
      parse_scenario_string(
          default_scenario_text() + "\n[materials]\n" + key + " = " + shortest_text(outside) + "\n",
          "s.toml");
      ADD_FAILURE() << key << " = " << outside << " was accepted";
    } catch (const UserError& e) {
      EXPECT_NE(e.where().find("materials." + key), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find("outside the supported range"), std::string::npos) << e.what();
    }
  }
}

TEST(MaterialsKeys, DocsSimulateMdListsExactlyTheTablesRows) {
  std::ifstream in(std::string(THAW_SOURCE_DIR) + "/docs/simulate.md");
  ASSERT_TRUE(in) << "docs/simulate.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string expected = key_docs_rows(materials_keys(), "[materials] ");
  EXPECT_NE(text.str().find(expected), std::string::npos)
      << "docs/simulate.md's [materials] rows differ from sim/scenario/materials_keys.cpp; they "
         "should read:\n"
      << expected;
}

}  // namespace
}  // namespace thaw::sim
