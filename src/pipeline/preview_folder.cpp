#include "src/pipeline/preview_folder.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "src/pipeline/pipeline.h"
#include "src/pipeline/run_manifest.h"
#include "src/pipeline/stage.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

fs::path settings_note(const fs::path& run_dir) {
  return run_dir / "run_items" / "render" / "image";
}

/// The folder holds finished frames or a film: its finals.
bool has_finals(const fs::path& dir) {
  std::error_code ec;
  return fs::exists(dir / "frames" / "frame_000000.png", ec) || fs::exists(dir / "melt.mp4", ec);
}

/// The stages whose outputs the render stage reads, nearest first (mesh, simulate).
std::vector<std::string> stages_before_render() {
  std::vector<std::string> names;
  for (const Stage* s = &stage_named("render"); !s->reads.empty();) {
    s = &stage_named(s->reads);
    names.push_back(s->name);
  }
  return names;
}

/// `from`'s files hard-linked (or copied) into the new folder `to`, written whole or not at all.
void link_tree(const fs::path& from, const fs::path& to) {
  StagingDirectory stage(to);
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(from)) {
    const fs::path target = stage.path() / e.path().lexically_relative(from);
    std::error_code ec;
    if (e.is_directory()) {
      fs::create_directories(target, ec);
    } else if (e.is_regular_file()) {
      fs::create_hard_link(e.path(), target, ec);
      if (ec) fs::copy_file(e.path(), target, ec);
    }
    if (ec)
      throw UserError(target.string(), "",
                      "cannot start the preview from " + e.path().string() + ": " + ec.message());
  }
  stage.commit();
}

}  // namespace

std::string ImageSettings::text() const {
  return std::to_string(width) + "x" + std::to_string(height) + ", " +
         std::to_string(samples_per_pixel) + " spp";
}

ImageSettings image_settings(const RunScenario& sc) {
  return {sc.scene.image.width, sc.scene.image.height, sc.scene.image.samples_per_pixel,
          sc.image_overridden};
}

void write_image_settings(const fs::path& run_dir, const ImageSettings& s) {
  char line[96];
  std::snprintf(line, sizeof line, "%dx%d spp %d%s\n", s.width, s.height, s.samples_per_pixel,
                s.command_line ? " command-line" : "");
  ensure_directory(settings_note(run_dir).parent_path());
  write_file_atomic(settings_note(run_dir), line);
}

std::optional<ImageSettings> read_image_settings(const fs::path& run_dir) {
  std::ifstream in(settings_note(run_dir));
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  ImageSettings s;
  char by = 0;
  std::string spp, flag;
  std::istringstream words(line);
  if (!(words >> s.width >> by >> s.height >> spp >> s.samples_per_pixel) || by != 'x' ||
      spp != "spp")
    return std::nullopt;
  s.command_line = static_cast<bool>(words >> flag) && flag == "command-line";
  return s;
}

RunFolder choose_run_folder(const RunScenario& sc, const RunOptions& o) {
  const fs::path dir = o.out_dir;
  if (o.preview_dir) {
    if (fs::weakly_canonical(*o.preview_dir) == fs::weakly_canonical(dir))
      throw UserError("", "--preview-dir",
                      "must differ from the run folder --out " + dir.string() +
                          " (the preview keeps that folder's finals)");
    return {*o.preview_dir, true,
            "preview: in " + o.preview_dir->string() + " (the finals in " + dir.string() +
                " are kept)"};
  }
  if (o.force || !has_finals(dir)) return {dir, false, ""};
  const ImageSettings run = image_settings(sc);
  const std::optional<ImageSettings> finals = read_image_settings(dir);
  if (finals && finals->same_image(run)) return {dir, false, ""};
  // A scenario edit makes a new final, unless the finals came from the command line.
  if (!run.command_line && !(finals && finals->command_line)) return {dir, false, ""};
  const fs::path preview = dir / "preview";
  return {preview, true,
          "preview: " + run.text() + " differs from the finals in " + dir.string() +
              (finals ? " (" + finals->text() + ")" : "") + ", so this run goes to " +
              preview.string() + " and keeps them (--force replaces the finals)"};
}

void start_preview_from(const fs::path& final_dir, const fs::path& preview_dir) {
  const RunManifest finals(final_dir / "run_manifest.json");
  ensure_directory(preview_dir);
  RunManifest preview(preview_dir / "run_manifest.json");
  // The stages DIR has complete, from the first (simulate) on: the preview starts from these.
  std::vector<std::pair<std::string, std::string>> complete;
  const std::vector<std::string> stages = stages_before_render();
  for (auto s = stages.rbegin(); s != stages.rend(); ++s) {
    if (!finals.is_complete(*s, finals.stage_hash(*s))) break;
    complete.emplace_back(*s, finals.stage_hash(*s));
  }
  bool same = true;
  for (const auto& [s, hash] : complete) same = same && preview.is_complete(s, hash);
  if (complete.empty() || same || !fs::is_directory(final_dir / "sim")) return;
  // The preview's record of these stages is forgotten before their files are replaced, so a run
  // killed in between redoes them rather than trusting a mix.
  for (const std::string& s : stages) preview.begin_stage(s, "");
  link_tree(final_dir / "sim", preview_dir / "sim");
  for (const auto& [s, hash] : complete) {
    preview.begin_stage(s, hash);
    preview.mark_stage_complete(s);
  }
}

}  // namespace thaw::pipeline
