// The [image] key table (render/scene/image_keys.h) against what reads it: the parser accepts
// every row's key and rejects values its rule rejects, find_scene_problem names the row's key,
// and docs/render.md's [image] rows are the table's, row for row.
#include "render/scene/image_keys.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

/// The docs' rows of the [image] keys, as the table writes them.
std::string expected_docs_rows() {
  return key_docs_rows(image_keys(), "[image] ");
}

TEST(ImageKeys, NamesAreUniqueAndFound) {
  std::set<std::string_view> names;
  for (const ImageKey& k : image_keys()) {
    EXPECT_TRUE(names.insert(k.name).second) << k.name;
    EXPECT_EQ(find_image_key(k.name), &k);
    EXPECT_FALSE(k.label.empty()) << k.name;
    EXPECT_FALSE(k.doc.empty()) << k.name;
  }
  EXPECT_EQ(find_image_key("no_such_key"), nullptr);
}

TEST(ImageKeys, DefaultsPassTheirRules) {
  const ImageSettings defaults;
  for (const ImageKey& k : image_keys())
    EXPECT_EQ(key_problem(k, defaults), std::nullopt) << k.name;
}

TEST(ImageKeys, FindSceneProblemNamesTheRowsKey) {
  for (const char* key : {"width", "samples_per_pixel", "exposure", "filter_radius"}) {
    const ImageKey* row = find_image_key(key);
    ASSERT_NE(row, nullptr);
    ImageSettings bad;
    if (const auto* k = std::get_if<IntegerKey<ImageSettings>>(&row->value)) bad.*(k->field) = -5;
    if (const auto* k = std::get_if<NumberKey<ImageSettings>>(&row->value)) bad.*(k->field) = 1e300;
    const auto problem = key_problem(*row, bad);
    ASSERT_TRUE(problem.has_value()) << key;
    SceneDescription scene;
    scene.image = bad;
    const auto found = find_scene_problem(scene);
    ASSERT_TRUE(found.has_value()) << key;
    EXPECT_EQ(found->key, "image." + std::string(key));
  }
}

TEST(ImageKeys, DocsRenderMdListsExactlyTheTablesRows) {
  std::ifstream in(std::string(THAW_SOURCE_DIR) + "/docs/render.md");
  ASSERT_TRUE(in) << "docs/render.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string expected = expected_docs_rows();
  EXPECT_NE(text.str().find(expected), std::string::npos)
      << "docs/render.md's [image] rows differ from render/scene/image_keys.cpp; they should "
         "read:\n"
      << expected;
}

}  // namespace
}  // namespace thaw::render
