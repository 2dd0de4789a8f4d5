#include "base/format/toml_table.h"

#include <gtest/gtest.h>

#include "base/error.h"

namespace thaw {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TomlTable, ReadsTypedValuesAndDefaults) {
  auto t =
      TomlTable::parse_string("a = 1.5\nb = 2\n[s]\nname = \"x\"\nv = [1, 2.5, 3]\n", "in.toml");
  EXPECT_DOUBLE_EQ(t.get_double("a"), 1.5);
  EXPECT_DOUBLE_EQ(t.get_double("b"), 2.0);  // integers are accepted as numbers
  EXPECT_DOUBLE_EQ(t.get_double("missing", 7.0), 7.0);
  auto s = t.table("s");
  EXPECT_EQ(s.get_string("name"), "x");
  const auto v = s.get_vec3("v");
  EXPECT_DOUBLE_EQ(v[1], 2.5);
  EXPECT_NO_THROW(t.check_no_unknown_keys());
}

TEST(TomlTable, UnknownKeyIsNamedWithItsLine) {
  auto t = TomlTable::parse_string("a = 1.0\n[shell]\ninner_radus_m = 0.02\n", "sc.toml");
  t.get_double("a");
  t.optional_table("shell");
  const std::string msg = error_of([&] { t.check_no_unknown_keys(); });
  EXPECT_NE(msg.find("sc.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("shell.inner_radus_m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key"), std::string::npos) << msg;
}

// Issue 27: a typo gets the nearest key of its table that the reader asked for.
TEST(TomlTable, UnknownKeySuggestsTheNearestKnownKey) {
  auto t = TomlTable::parse_string(
      "[camera]\nvertical_fov = 35.0\n[shell]\ninner_radus_m = 0.02\nzzz = 1\n", "sc.toml");
  auto camera = t.table("camera");
  camera.get_double("vertical_fov_deg", 40.0);  // asked for, absent: still a known key
  camera.get_double("position", 0.0);
  std::string msg = error_of([&] { t.check_no_unknown_keys(); });
  EXPECT_NE(msg.find("camera.vertical_fov"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean 'vertical_fov_deg'?"), std::string::npos) << msg;
  auto u = TomlTable::parse_string("[shell]\ninner_radus_m = 0.02\nzzz = 1\n", "sc.toml");
  auto shell = u.table("shell");
  shell.get_double("inner_radius_m", 0.02);
  shell.get_double("outer_radius_m", 0.03);
  msg = error_of([&] { u.check_no_unknown_keys(); });
  EXPECT_NE(msg.find("did you mean 'inner_radius_m'?"), std::string::npos) << msg;
  // Nothing near: no suggestion.
  auto v = TomlTable::parse_string("[shell]\nzzz = 1\n", "sc.toml");
  v.table("shell").get_double("inner_radius_m", 0.02);
  msg = error_of([&] { v.check_no_unknown_keys(); });
  EXPECT_NE(msg.find("unknown key"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("did you mean"), std::string::npos) << msg;
}

TEST(TomlTable, UnreadTableIsUnknown) {
  auto t = TomlTable::parse_string("[extra]\nx = 1\n", "sc.toml");
  EXPECT_NE(error_of([&] { t.check_no_unknown_keys(); }).find("'extra'"), std::string::npos);
}

TEST(TomlTable, ArrayOfTablesTracksEachElement) {
  auto t = TomlTable::parse_string("[[o]]\nr = 1\n[[o]]\nr = 2\nq = 3\n", "s.toml");
  for (const auto& o : t.array_of_tables("o")) o.get_double("r");
  EXPECT_NE(error_of([&] { t.check_no_unknown_keys(); }).find("o[1].q"), std::string::npos);
}

TEST(TomlTable, RejectsNonFiniteAndWrongTypes) {
  auto t = TomlTable::parse_string("a = nan\nb = inf\nc = \"1\"\nd = [1, 2]\n", "s.toml");
  EXPECT_NE(error_of([&] { t.get_double("a"); }).find("finite"), std::string::npos);
  EXPECT_NE(error_of([&] { t.get_double("b"); }).find("finite"), std::string::npos);
  EXPECT_NE(error_of([&] { t.get_double("c"); }).find("expected a number"), std::string::npos);
  EXPECT_NE(error_of([&] { t.get_vec3("d"); }).find("3 numbers"), std::string::npos);
  EXPECT_NE(error_of([&] { t.get_double("zz"); }).find("missing"), std::string::npos);
}

TEST(TomlTable, MalformedTomlNamesFileAndLine) {
  const std::string msg = error_of([] { TomlTable::parse_string("a = 1\nb = = 2\n", "bad.toml"); });
  EXPECT_NE(msg.find("bad.toml: line 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("malformed TOML"), std::string::npos) << msg;
}

TEST(TomlTable, MissingFile) {
  const std::string msg = error_of([] { TomlTable::parse_file("/nonexistent/x.toml"); });
  EXPECT_EQ(msg, "/nonexistent/x.toml: no such file");
}

TEST(TomlTable, RangeHelpersQuoteTheValue) {
  auto t = TomlTable::parse_string("r = -0.5\n", "s.toml");
  const double r = t.get_double("r");
  const std::string msg = error_of([&] { t.require_positive("r", r); });
  EXPECT_NE(msg.find("must be positive (got -0.5)"), std::string::npos) << msg;
}

}  // namespace
}  // namespace thaw

namespace thaw {
namespace {
TEST(TomlTable, CanonicalTextIgnoresLayoutButNotValues) {
  auto a = TomlTable::parse_string("[r]\nx = 1.0 # comment\ny = [1, 2]\n", "a.toml");
  auto b = TomlTable::parse_string("[r]\ny = [ 1,2 ]\n\nx = 1.0\n", "b.toml");
  auto c = TomlTable::parse_string("[r]\nx = 1.5\ny = [1, 2]\n", "c.toml");
  EXPECT_EQ(a.table("r").canonical_text(), b.table("r").canonical_text());
  EXPECT_NE(a.table("r").canonical_text(), c.table("r").canonical_text());
}
}  // namespace
}  // namespace thaw

namespace thaw {
namespace {
TEST(TomlTable, IsAnswersTheTypeWithoutMarkingTheKeyRead) {
  auto t = TomlTable::parse_string("b = true\ns = \"x\"\ni = 3\nf = 2.5\n[t]\nk = 1\n", "q.toml");
  EXPECT_TRUE(t.is<bool>("b"));
  EXPECT_FALSE(t.is<bool>("s"));
  EXPECT_TRUE(t.is<std::string>("s"));
  EXPECT_TRUE(t.is<double>("i"));  // any number reads as a double
  EXPECT_TRUE(t.is<double>("f"));
  EXPECT_TRUE(t.is<std::int64_t>("i"));
  EXPECT_FALSE(t.is<std::int64_t>("f"));
  EXPECT_TRUE(t.is<TomlTable>("t"));
  EXPECT_FALSE(t.is<TomlTable>("missing"));
  EXPECT_FALSE(t.is<bool>("missing"));
  // Nothing was read: every key is still unknown to check_no_unknown_keys.
  EXPECT_THROW(t.check_no_unknown_keys(), UserError);
}
}  // namespace
}  // namespace thaw
