// The shape rules of a tabulated spectrum (render/media/wavelength_table.h), and that the index
// model and the absorption report a table's problem under their own key in the same words.
#include "render/media/wavelength_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/error.h"
#include "render/media/absorption.h"
#include "render/media/ior_model.h"

namespace thaw::render::media {
namespace {

const TableValues kIndex{"n", 1.0, "a finite number >= 1"};

std::string problem_key(const std::vector<double>& nm, const std::vector<double>& v) {
  const auto p = wavelength_table_problem(nm, v, kIndex);
  return p ? p->key + ": " + p->problem : "ok";
}

TEST(WavelengthTable, EachRuleNamesItsKey) {
  EXPECT_EQ(problem_key({380, 780}, {1.31, 1.30}), "ok");
  EXPECT_EQ(problem_key({380, 780}, {1.31}), ": wavelength_nm has 2 entries but n has 1");
  EXPECT_EQ(problem_key({380}, {1.31}), ": a table needs at least two rows");
  EXPECT_EQ(problem_key({380, 600, 600, 780}, {1.3, 1.3, 1.3, 1.3}),
            "wavelength_nm: must be strictly increasing (row 2)");
  EXPECT_EQ(problem_key({380, NAN, 780}, {1.3, 1.3, 1.3}),
            "wavelength_nm: must be strictly increasing (row 1)");
  EXPECT_EQ(problem_key({390, 780}, {1.3, 1.3}),
            "wavelength_nm: covers 390-780 nm but must cover the rendered range 380-780 nm");
  EXPECT_EQ(problem_key({380, 770}, {1.3, 1.3}),
            "wavelength_nm: covers 380-770 nm but must cover the rendered range 380-780 nm");
  EXPECT_EQ(problem_key({380, 780}, {1.3, 0.99}),
            "n: entry 1 must be a finite number >= 1 (got 0.99)");
  EXPECT_EQ(problem_key({380, 780}, {INFINITY, 1.3}),
            "n: entry 0 must be a finite number >= 1 (got inf)");
}

std::string message_of(const auto& validate) {
  try {
    validate();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(WavelengthTable, IndexAndAbsorptionUseTheRuleUnderTheirKeys) {
  const std::string ior = message_of([] {
    IorModel::table({380, 700}, {1.31, 1.30}).validate("scene.toml", "media.ice");
  });
  EXPECT_NE(ior.find("'media.ice.table.wavelength_nm'"), std::string::npos) << ior;
  EXPECT_NE(ior.find("must cover the rendered range 380-780 nm"), std::string::npos) << ior;
  const std::string absorption = message_of([] {
    Absorption::table({380, 780}, {0.1, -0.2}).validate("scene.toml", "media.ice");
  });
  EXPECT_NE(absorption.find("'media.ice.absorption_per_m.per_m'"), std::string::npos) << absorption;
  EXPECT_NE(absorption.find("entry 1 must be finite and >= 0 per metre (got -0.2)"),
            std::string::npos)
      << absorption;
}

}  // namespace
}  // namespace thaw::render::media
