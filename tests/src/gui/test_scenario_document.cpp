// ScenarioDocument: edits land in the TOML document, saving round-trips (the saved file parses to
// the same scenario and keeps keys the GUI has no field for), and problems come from the
// scenario parser itself, naming the key.
#include "src/gui/scenario_document.h"

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/format/toml_table.h"

namespace thaw::gui {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("thaw_gui_doc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

TEST(ScenarioDocument, DefaultIsValidAndParsesAsTheBuiltInDefault) {
  const ScenarioDocument doc;
  const ScenarioCheck c = doc.check();
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_EQ(c.scenario->simulation_text, pipeline::default_run_scenario().simulation_text);
  EXPECT_EQ(c.scenario->render_text, pipeline::default_run_scenario().render_text);
}

TEST(ScenarioDocument, EditSaveReloadGivesTheSameScenario) {
  ScenarioDocument doc;
  doc.set("shell.outer_radius_m", 0.035);
  doc.set("render.image.background", std::array<double, 3>{0.1, 0.2, 0.3});
  doc.set("film.frames", 12LL);
  const fs::path file = temp_file("edited.toml");
  doc.save(file);
  const ScenarioDocument back = ScenarioDocument::load(file);
  const ScenarioCheck a = doc.check(), b = back.check();
  ASSERT_TRUE(b.ok()) << b.message;
  EXPECT_DOUBLE_EQ(b.scenario->simulation.outer_radius_m, 0.035);
  EXPECT_EQ(b.scenario->film.frames, 12);
  EXPECT_EQ(b.scenario->scene.image.background, (render::RgbD{0.1, 0.2, 0.3}));
  EXPECT_EQ(a.scenario->simulation_text, b.scenario->simulation_text);
  EXPECT_EQ(a.scenario->film_text, b.scenario->film_text);
  EXPECT_EQ(a.scenario->mesh_text, b.scenario->mesh_text);
  EXPECT_EQ(a.scenario->render_text, b.scenario->render_text);
  EXPECT_EQ(doc.text(), back.text());
}

TEST(ScenarioDocument, KeysWithoutAFieldSurviveASave) {
  // [mesh] angle_deg and [render.caustics] have no widget in the GUI; they must be kept.
  const std::string text =
      std::string(pipeline::default_run_scenario_text()) + "\n[render.caustics]\nphotons = 12345\n";
  ScenarioDocument doc = ScenarioDocument::from_text(text, "kept.toml");
  doc.set("mesh.angle_deg", 25.0);
  doc.set("shell.inner_radius_m", 0.015);
  const fs::path file = temp_file("kept.toml");
  doc.save(file);
  const ScenarioCheck c = ScenarioDocument::load(file).check();
  ASSERT_TRUE(c.ok()) << c.message;
  ASSERT_TRUE(c.scenario->scene.caustics.photons.has_value());
  EXPECT_EQ(*c.scenario->scene.caustics.photons, 12345);
  EXPECT_DOUBLE_EQ(c.scenario->mesh.angle_deg, 25.0);
  EXPECT_DOUBLE_EQ(c.scenario->simulation.inner_radius_m, 0.015);
}

TEST(ScenarioDocument, AProblemComesFromTheParserWithItsKeyAndBlocksSaving) {
  ScenarioDocument doc;
  doc.set("shell.inner_radius_m", 0.05);  // larger than the outer radius 0.03
  const ScenarioCheck c = doc.check();
  ASSERT_FALSE(c.ok());
  // The same message the file would give (the parser's), naming the key.
  try {
    (void)pipeline::parse_run_scenario(TomlTable::parse_string(doc.text(), doc.source_name()));
    FAIL() << "the parser accepted what check() refused";
  } catch (const UserError& e) {
    EXPECT_EQ(c.message, e.what());
  }
  EXPECT_FALSE(c.key.empty());
  EXPECT_NE(c.key.find("radius"), std::string::npos) << c.key;
  const fs::path file = temp_file("refused.toml");
  fs::remove(file);
  EXPECT_THROW(doc.save(file), UserError);
  EXPECT_FALSE(fs::exists(file));
}

TEST(ScenarioDocument, ArraysOfTablesAreEditedInPlace) {
  ScenarioDocument doc;
  const std::size_t before = doc.array_size("render.objects");
  const std::size_t k = doc.append_table("render.objects");
  EXPECT_EQ(k, before);
  const std::string key = "render.objects[" + std::to_string(k) + "]";
  doc.set(key + ".shape", std::string("sphere"));
  doc.set(key + ".center", std::array<double, 3>{0.05, 0.01, 0});
  doc.set(key + ".radius", 0.01);
  doc.set(key + ".material", std::string("floor"));
  ScenarioCheck c = doc.check();
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_EQ(c.scenario->scene.objects.size(), before + 1);
  doc.erase_table("render.objects", k);
  c = doc.check();
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_EQ(c.scenario->scene.objects.size(), before);
}

TEST(ScenarioDocument, ElementsOfArraysAreSetInPlace) {
  // The default floor's checker colours: [[0.9, 0.9, 0.9], [0.6, 0.08, 0.08]].
  ScenarioDocument doc;
  doc.set("render.materials.floor.checker.colors[1]", std::array<double, 3>{0.1, 0.3, 0.6});
  const ScenarioCheck c = doc.check();
  ASSERT_TRUE(c.ok()) << c.message << "\n" << doc.text();
  EXPECT_EQ(c.scenario->scene.materials.front().texture.checker_colors[1],
            (render::RgbD{0.1, 0.3, 0.6}));
  EXPECT_EQ(c.scenario->scene.materials.front().texture.checker_colors[0],
            (render::RgbD{0.9, 0.9, 0.9}));
  const auto v = doc.value("render.materials.floor.checker.colors[1]");
  ASSERT_TRUE(v.has_value());
  using V3 = std::array<double, 3>;
  EXPECT_EQ(std::get<V3>(*v), (V3{0.1, 0.3, 0.6}));
}

/// The comments of `text` in order (from '#' to the end of the line; the files used here have
/// no '#' inside strings).
std::vector<std::string> comments(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (const auto hash = line.find('#'); hash != std::string::npos)
      out.push_back(line.substr(hash));
  return out;
}

TEST(ScenarioDocument, SaveKeepsTheCommentsAndLayoutOfTheFileItLoaded) {
  // The edits the window makes: values, a new key, a new table ([render.camera] after an orbit),
  // a checker colour inside an inline table, an object added, filled and removed again.
  const std::string original = pipeline::default_run_scenario_text();
  const fs::path source = temp_file("commented.toml");
  write_file_atomic(source, original);
  ScenarioDocument doc = ScenarioDocument::load(source);
  doc.set("shell.outer_radius_m", 0.035);
  doc.set("film.frames", 12LL);
  doc.set("mesh.angle_deg", 25.0);
  doc.set("render.camera.position", std::array<double, 3>{0.0, 0.08, 0.2});
  doc.set("render.camera.look_at", std::array<double, 3>{0.0, 0.02, 0.0});
  doc.set("render.camera.up", std::array<double, 3>{0.0, 1.0, 0.0});
  doc.set("render.camera.vertical_fov_deg", 35.0);
  doc.set("render.materials.floor.checker.colors[1]", std::array<double, 3>{0.1, 0.3, 0.6});
  const std::size_t k = doc.append_table("render.objects");
  doc.set("render.objects[" + std::to_string(k) + "].shape", std::string("sphere"));
  doc.erase_table("render.objects", k);
  EXPECT_TRUE(doc.layout_kept());
  const fs::path file = temp_file("commented_saved.toml");
  doc.save(file);
  const ScenarioDocument back = ScenarioDocument::load(file);
  EXPECT_EQ(comments(back.text()), comments(original));
  // Only the edited lines differ: each edit is visible as itself.
  const std::string saved = back.text();
  EXPECT_NE(saved.find("outer_radius_m = 0.035          # outer ice surface at t = 0\n"),
            std::string::npos)
      << saved;
  EXPECT_NE(saved.find("frames = 12                    # spread evenly"), std::string::npos);
  EXPECT_NE(saved.find("edge_length_m = 2.5e-3         # target triangle edge; see docs/mesh.md "
                       "for the trade-off\nangle_deg = 25.0\n"),
            std::string::npos);
  EXPECT_NE(saved.find("[render.camera]\nposition = [0.0, 0.08, 0.2]\nlook_at = [0.0, 0.02, 0.0]"),
            std::string::npos);
  EXPECT_NE(saved.find("colors = [[0.9, 0.9, 0.9], [0.1, 0.3, 0.6]], size = 0.02"),
            std::string::npos);
  const ScenarioCheck c = back.check();
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_DOUBLE_EQ(c.scenario->simulation.outer_radius_m, 0.035);
  EXPECT_EQ(c.scenario->film.frames, 12);
  EXPECT_DOUBLE_EQ(c.scenario->mesh.angle_deg, 25.0);
  EXPECT_EQ(c.scenario->scene.objects.size(),
            pipeline::default_run_scenario().scene.objects.size());
  EXPECT_EQ(c.scenario->render_text, doc.check().scenario->render_text);
}

TEST(ScenarioDocument, EveryDataScenarioKeepsItsCommentsThroughAValueEdit) {
  for (const auto& e : fs::directory_iterator(fs::path(THAW_SOURCE_DIR) / "data/scenarios")) {
    if (e.path().extension() != ".toml") continue;
    ScenarioDocument doc = ScenarioDocument::load(e.path());
    const std::string original = doc.text();
    // (a scenario for `thaw simulate` alone may lack what `thaw run` needs: only the text counts)
    const bool runnable = doc.check().ok();
    // (a file without [render] would gain one, which then needs its media: not this test's point)
    const bool has_image = doc.has("render.image");
    if (has_image) doc.set("render.image.background", std::array<double, 3>{0.5, 0.25, 0.125});
    doc.set("film.fps", 24.0);
    EXPECT_TRUE(doc.layout_kept()) << e.path();
    EXPECT_EQ(comments(doc.text()), comments(original)) << e.path();
    const ScenarioCheck c = doc.check();
    if (!runnable) continue;
    ASSERT_TRUE(c.ok()) << e.path() << ": " << c.message;
    if (has_image) {
      EXPECT_EQ(c.scenario->scene.image.background, (render::RgbD{0.5, 0.25, 0.125})) << e.path();
    }
    EXPECT_DOUBLE_EQ(c.scenario->film.fps, 24.0) << e.path();
  }
}

TEST(ScenarioDocument, ALayoutNotEditableInPlaceIsReserialisedCorrectly) {
  // [render.image] written with dotted keys under [render]: a new key cannot go in place; the
  // document is re-serialised (comments lost, said by layout_kept) and still right.
  std::string text = pipeline::default_run_scenario_text();
  const auto header = text.find("[render.image]\n");
  ASSERT_NE(header, std::string::npos);
  text.replace(header, 15, "[render]\n");
  // Every key line of the section, up to the next header, becomes image.KEY.
  for (auto at = text.find('\n', header) + 1; at < text.size() && text[at] != '[';
       at = text.find('\n', at) + 1)
    if (std::isalpha(static_cast<unsigned char>(text[at]))) text.insert(at, "image.");
  ScenarioDocument doc = ScenarioDocument::from_text(text, "dotted.toml");
  ASSERT_TRUE(doc.check().ok()) << doc.check().message;
  doc.set("render.image.exposure", 0.5);
  EXPECT_FALSE(doc.layout_kept());
  const ScenarioCheck c = doc.check();
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_DOUBLE_EQ(c.scenario->scene.image.exposure, 0.5);
  EXPECT_EQ(c.scenario->scene.image.width, 640);
}

TEST(ScenarioDocument, KeyOfProblem) {
  EXPECT_EQ(key_of_problem("line 3, key 'shell.inner_radius_m'"), "shell.inner_radius_m");
  EXPECT_EQ(key_of_problem("line 3"), "");
}

}  // namespace
}  // namespace thaw::gui

namespace thaw::gui {
namespace {

// A grid scenario's [shape] bodies are inline tables (issue 25 item 6): a box's size typed in
// the Scenario tab is written into its inline table in place, the file's comments kept.
TEST(ScenarioDocument, AShapeSizeIsEditedInPlace) {
  const std::string text =
      "# a hollow cube\n"
      "[simulation]\n"
      "geometry = \"3d\"\n"
      "\n"
      "[shape]\n"
      "outer  = { kind = \"box\", size_m = [0.04, 0.04, 0.04] }\n"
      "cavity = { kind = \"box\", size_m = [0.024, 0.024, 0.024] }\n"
      "\n"
      "[water]\n"
      "initial_temperature_c = 10.0\n";
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "thaw_gui_document_shape.toml";
  write_file_atomic(file, text);
  ScenarioDocument doc = ScenarioDocument::load(file);
  doc.set("shape.outer.size_m", std::array<double, 3>{0.05, 0.04, 0.045});
  EXPECT_TRUE(doc.layout_kept()) << doc.text();
  EXPECT_NE(doc.text().find("size_m = [0.05, 0.04, 0.045]"), std::string::npos) << doc.text();
  std::filesystem::remove(file);
  ScenarioDocument cube = ScenarioDocument::load(std::filesystem::path(THAW_SOURCE_DIR) /
                                                 "data/scenarios/hollow_cube.toml");
  // A copy (the window's) edits in place as well.
  ScenarioDocument copy = cube;
  cube.set("shape.outer.size_m", std::array<double, 3>{0.05, 0.04, 0.045});
  EXPECT_TRUE(cube.layout_kept()) << cube.text();
  copy.set("shape.outer.size_m", std::array<double, 3>{0.05, 0.04, 0.045});
  EXPECT_TRUE(copy.layout_kept()) << copy.text();
  EXPECT_EQ(copy.text(), cube.text());
}

}  // namespace
}  // namespace thaw::gui
