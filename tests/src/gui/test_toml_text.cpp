// toml_text: in-place edits of a TOML file's text. Each test states the exact text an edit must
// give (the original with only that value's span or line changed), so a comment moved, lost or
// duplicated fails; the edited text must also parse to the table the edit intends.
#include "src/gui/toml_text.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <string>

namespace thaw::gui::toml_text {
namespace {

toml::table parse(const std::string& text) {
  return toml::parse(std::string_view(text), std::string_view("test.toml"));
}

/// `text` with its only occurrence of `from` replaced by `to` (fails if not exactly one).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

const std::string kText =
    "# a file with comments\n"
    "[shell]  # the shell\n"
    "inner_radius_m = 0.02          # water core\n"
    "outer_radius_m = 0.03          # outer ice\n"
    "\n"
    "[render.materials.floor]\n"
    "kind = \"matte\"\n"
    "checker = { colors = [[0.9, 0.9, 0.9], [0.6, 0.08, 0.08]], size = 0.02 }\n"
    "\n"
    "[[render.objects]]\n"
    "shape = \"plane\"   # the floor\n"
    "material = \"floor\"\n";

/// Sets `key` to `value` in a copy of `parsed` (what the document's table does).
template <class T>
toml::table set_in(toml::table t, const std::string& table_path, const std::string& name, T value) {
  toml::table* at = &t;
  std::string::size_type b = 0;
  while (b < table_path.size()) {
    const auto e = table_path.find('.', b);
    const std::string part = table_path.substr(b, e == std::string::npos ? e : e - b);
    toml::table* next = at->get_as<toml::table>(part);
    if (!next) next = at->insert_or_assign(part, toml::table{}).first->second.as_table();
    at = next;
    b = e == std::string::npos ? table_path.size() : e + 1;
  }
  at->insert_or_assign(name, value);
  return t;
}

TEST(TomlText, FormatValueIsShortestExactAndTyped) {
  EXPECT_EQ(format_value(toml::value<double>(0.1)), "0.1");
  EXPECT_EQ(format_value(toml::value<double>(25.0)), "25.0");
  EXPECT_EQ(format_value(toml::value<double>(-2.5e-3)), "-0.0025");
  EXPECT_EQ(format_value(toml::value<double>(1e-6)), "1e-06");
  EXPECT_EQ(format_value(toml::value<std::int64_t>(12)), "12");
  EXPECT_EQ(format_value(toml::value<bool>(true)), "true");
  EXPECT_EQ(format_value(toml::value<std::string>("a \"b\"\\")), "\"a \\\"b\\\"\\\\\"");
  EXPECT_EQ(format_value(toml::array{0.25, 0.3, 0.4}), "[0.25, 0.3, 0.4]");
  EXPECT_EQ(format_value(toml::table{{"size", 0.02}}), "{ size = 0.02 }");
  // Every form reads back as the same value and type.
  for (const double v : {0.1, 25.0, 1e-6, 1.0 / 3.0, 6.02214076e23, -0.0}) {
    const toml::table back = parse("x = " + format_value(toml::value<double>(v)));
    ASSERT_TRUE(back["x"].is_floating_point()) << v;
    EXPECT_EQ(*back["x"].value<double>(), v);
  }
}

TEST(TomlText, AChangedValueRewritesOnlyItsSpan) {
  const toml::table t = parse(kText);
  const auto key = split_key("shell.outer_radius_m");
  const toml::table want = set_in(t, "shell", "outer_radius_m", 0.035);
  const auto text = with_value(kText, t, key, want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, replaced(kText, "outer_radius_m = 0.03 ", "outer_radius_m = 0.035 "));
  EXPECT_EQ(parse(*text), want);
}

TEST(TomlText, AnElementInsideAnInlineTableRewritesOnlyThatElement) {
  const toml::table t = parse(kText);
  toml::table want = t;
  want["render"]["materials"]["floor"]["checker"]["colors"].as_array()->replace(
      want["render"]["materials"]["floor"]["checker"]["colors"].as_array()->begin() + 1,
      toml::array{0.1, 0.3, 0.6});
  const auto text =
      with_value(kText, t, split_key("render.materials.floor.checker.colors[1]"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, replaced(kText, "[0.6, 0.08, 0.08]", "[0.1, 0.3, 0.6]"));
  EXPECT_EQ(parse(*text), want);
}

// A [shape] body is an inline table (issue 25): a whole array inside it (a box's size_m) is
// rewritten in place, and so is a key added to it.
TEST(TomlText, AnArrayOrAKeyOfAnInlineTableIsEditedInPlace) {
  const std::string text =
      "# a grid body\n"
      "[shape]\n"
      "outer  = { kind = \"box\", size_m = [0.04, 0.04, 0.04] }  # the cube\n"
      "cavity = { kind = \"sphere\", radius_m = 0.01 }\n";
  const toml::table t = parse(text);
  toml::table want = t;
  want["shape"]["outer"].as_table()->insert_or_assign("size_m", toml::array{0.05, 0.04, 0.045});
  const auto edited = with_value(text, t, split_key("shape.outer.size_m"), want);
  ASSERT_TRUE(edited.has_value());
  EXPECT_EQ(*edited, replaced(text, "[0.04, 0.04, 0.04]", "[0.05, 0.04, 0.045]"));
  EXPECT_EQ(parse(*edited), want);
  toml::table added = t;
  added["shape"]["cavity"].as_table()->insert_or_assign("center_m", toml::array{0.0, 0.01, 0.0});
  const auto with_key = with_value(text, t, split_key("shape.cavity.center_m"), added);
  ASSERT_TRUE(with_key.has_value());
  EXPECT_EQ(parse(*with_key), added);
  EXPECT_NE(with_key->find("# the cube"), std::string::npos);
}

TEST(TomlText, ColumnsCountCodePointsNotBytes) {
  // toml++ positions count code points: the element after "é" (2 bytes) is found exactly.
  const std::string original = "x = [\"é\", 2]  # ü\n";
  const toml::table t = parse(original);
  toml::table want = t;
  want["x"].as_array()->replace(want["x"].as_array()->begin() + 1, std::int64_t{3});
  const auto text = with_value(original, t, split_key("x[1]"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, "x = [\"é\", 3]  # ü\n");
}

TEST(TomlText, ANewKeyGoesAfterTheLastKeyOfItsTable) {
  const toml::table t = parse(kText);
  const toml::table want = set_in(t, "shell", "note", std::string("thin"));
  const auto text = with_value(kText, t, split_key("shell.note"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, replaced(kText, "# outer ice\n", "# outer ice\nnote = \"thin\"\n"));
  EXPECT_EQ(parse(*text), want);
}

TEST(TomlText, ANewTableIsAppendedWithItsHeader) {
  const toml::table t = parse(kText);
  toml::table want = t;
  want["render"].as_table()->insert_or_assign(
      "camera", toml::table{{"position", toml::array{0.0, 0.075, 0.17}}});
  const auto text = with_value(kText, t, split_key("render.camera.position"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, kText + "\n[render.camera]\nposition = [0.0, 0.075, 0.17]\n");
  EXPECT_EQ(parse(*text), want);
}

TEST(TomlText, RemovingAKeyOrATableDeletesTheirLinesOnly) {
  const toml::table t = parse(kText);
  toml::table want = t;
  want["shell"].as_table()->erase("inner_radius_m");
  auto text = without(kText, t, split_key("shell.inner_radius_m"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, replaced(kText, "inner_radius_m = 0.02          # water core\n", ""));
  EXPECT_EQ(parse(*text), want);

  // An implicit table ([render.materials] made by its sub-table's header) goes with its
  // sub-tables.
  want = t;
  want["render"].as_table()->erase("materials");
  text = without(kText, t, split_key("render.materials"), want);
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(*text, replaced(kText,
                            "[render.materials.floor]\nkind = \"matte\"\n"
                            "checker = { colors = [[0.9, 0.9, 0.9], [0.6, 0.08, 0.08]], size = "
                            "0.02 }\n\n",
                            ""));
  EXPECT_EQ(parse(*text), want);
}

TEST(TomlText, AnAppendedTableOfAnArrayIsErasedBackToTheOriginalText) {
  const toml::table t = parse(kText);
  const auto key = split_key("render.objects");
  const auto added = with_table_appended(kText, t, key);
  ASSERT_TRUE(added.has_value());
  EXPECT_EQ(*added, kText + "\n[[render.objects]]\n");
  const toml::table t2 = parse(*added);
  ASSERT_EQ(t2["render"]["objects"].as_array()->size(), 2u);
  toml::table want = t2;
  want["render"]["objects"][1].as_table()->insert_or_assign("shape", "sphere");
  const auto filled = with_value(*added, t2, split_key("render.objects[1].shape"), want);
  ASSERT_TRUE(filled.has_value());
  EXPECT_EQ(*filled, kText + "\n[[render.objects]]\nshape = \"sphere\"\n");
  const auto erased = without_table(*filled, parse(*filled), key, 1);
  ASSERT_TRUE(erased.has_value());
  EXPECT_EQ(*erased, kText);
  // The first entry, with its comment line.
  const auto first = without_table(kText, t, key, 0);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(*first, replaced(kText,
                             "\n[[render.objects]]\nshape = \"plane\"   # the floor\n"
                             "material = \"floor\"\n",
                             ""));
}

TEST(TomlText, ALayoutItDoesNotEditInPlaceIsRefused) {
  // A table defined by dotted keys has no header to insert under: nullopt, the caller
  // re-serialises.
  const std::string dotted = "[a]\nb.c = 1\n";
  const toml::table t = parse(dotted);
  toml::table want = t;
  want["a"]["b"].as_table()->insert_or_assign("d", std::int64_t{2});
  EXPECT_FALSE(with_value(dotted, t, split_key("a.b.d"), want).has_value());
}

}  // namespace
}  // namespace thaw::gui::toml_text
