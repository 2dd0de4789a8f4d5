#pragma once
// Previews never overwrite finals. A run folder's frames and film are its finals; a `thaw run`
// that asks for other image settings (--size / --spp) than those the finals were rendered with
// is a preview: it runs in DIR/preview/ (or the folder given by --preview-dir), which starts
// from DIR's simulation and meshes (hard links, so nothing is simulated or meshed twice and
// nothing in DIR can change), and says where. --force replaces the finals instead. A run without
// --size / --spp renders into DIR as before (a scenario edit is a new final), unless the finals
// themselves were rendered with --size / --spp (a large final is kept from a plain rerun too).
// Knows the stages only through stage.h (the ones the render stage reads).
#include <filesystem>
#include <optional>
#include <string>

#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

struct RunOptions;

/// The image settings frames were rendered with: DIR/run_items/render/image, one line
/// "640x480 spp 8" (+ " command-line" when given by --size / --spp).
struct ImageSettings {
  int width = 0, height = 0, samples_per_pixel = 0;
  /// set by --size / --spp rather than the scenario
  bool command_line = false;
  bool same_image(const ImageSettings& o) const {
    return width == o.width && height == o.height && samples_per_pixel == o.samples_per_pixel;
  }
  /// "640x480, 8 spp"
  std::string text() const;
};

ImageSettings image_settings(const RunScenario& scenario);
/// Writes the note for the frames about to be rendered into `run_dir`.
void write_image_settings(const std::filesystem::path& run_dir, const ImageSettings& settings);
/// The note of `run_dir`, if any (a folder made before the note existed has none).
std::optional<ImageSettings> read_image_settings(const std::filesystem::path& run_dir);

/// Where this run goes: DIR itself, or a preview folder beside its finals.
struct RunFolder {
  std::filesystem::path dir;
  /// a preview: `dir` is the preview folder; `why` says why and where, for the user
  bool preview = false;
  std::string why;
};

/// Decides (reading DIR only) where a run of `scenario` with `options` goes.
RunFolder choose_run_folder(const RunScenario& scenario, const RunOptions& options);

/// Makes `preview_dir` start from `final_dir`'s simulation and meshes where those stages are
/// complete there: SIM/ hard-linked (copied where links cannot be made) and the stages recorded
/// complete under the same fingerprints. A preview whose inputs differ redoes them itself, in its
/// own folder (every output is written under a temporary name and renamed, so a hard-linked file
/// in DIR is never written through).
void start_preview_from(const std::filesystem::path& final_dir,
                        const std::filesystem::path& preview_dir);

}  // namespace thaw::pipeline
