#pragma once
// What `thaw run` has finished, so a rerun redoes only what changed: per stage the fingerprint
// of its inputs (relevant scenario sections + upstream outputs) and the items completed under it.
// Saved atomically after every item, so killing the run at any moment leaves a valid manifest.
#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace thaw::pipeline {

class RunManifest {
 public:
  /// Loads `file`; a missing file gives an empty manifest. A file that cannot be parsed (only
  /// possible if edited by hand: saves are atomic) is ignored, so everything is redone.
  explicit RunManifest(std::filesystem::path file);

  /// Starts (or resumes) `stage` with inputs fingerprinted by `input_hash`. If the fingerprint
  /// differs from the recorded one, the stage's finished items are forgotten. Returns true if the
  /// stage was already complete under this very fingerprint.
  bool begin_stage(const std::string& stage, const std::string& input_hash);
  bool item_done(const std::string& stage, const std::string& item) const;
  /// Records an item as done (after its output was renamed into place) and saves.
  void mark_item_done(const std::string& stage, const std::string& item);
  /// Records the stage as complete and saves.
  void mark_stage_complete(const std::string& stage);
  /// Forgets everything (--force) and saves.
  void clear();
  std::string stage_hash(const std::string& stage) const;

 private:
  struct Stage {
    std::string input_hash;
    bool complete = false;
    std::set<std::string> items;
  };
  void save() const;
  std::filesystem::path m_file;
  std::map<std::string, Stage> m_stages;
};

}  // namespace thaw::pipeline
