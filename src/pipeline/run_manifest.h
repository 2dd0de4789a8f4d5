#pragma once
// What `thaw run` has finished, so a rerun redoes only what changed: per stage the fingerprint
// of its inputs (relevant scenario sections + upstream outputs) and the items completed under it.
// Saved atomically, so killing the run at any moment leaves a valid manifest. Finished items are
// one small file each (DIR/run_items/STAGE/ITEM holding the stage's input hash), so processes
// sharing a run (MPI ranks, Slurm array tasks, GNU parallel jobs) record their items without
// rewriting each other's: only the process coordinating the run saves run_manifest.json.
#include <filesystem>
#include <map>
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
  /// True if `stage` was completed under `input_hash` (changes nothing).
  bool is_complete(const std::string& stage, const std::string& input_hash) const;
  bool item_done(const std::string& stage, const std::string& item) const;
  /// Records an item as done (after its output was renamed into place): writes its item file,
  /// the stage's input hash on the first line and, if given, `note` (one line, for people and
  /// benchmarks: what the item cost, say) on the second.
  void mark_item_done(const std::string& stage, const std::string& item,
                      const std::string& note = "");
  /// Records the stage as complete and saves.
  void mark_stage_complete(const std::string& stage);
  /// Forgets everything (--force): saves and removes the item files.
  void clear();
  std::string stage_hash(const std::string& stage) const;

 private:
  struct Stage {
    std::string input_hash;
    bool complete = false;
  };
  void save() const;
  std::filesystem::path item_file(const std::string& stage, const std::string& item) const;
  std::filesystem::path m_file, m_items_dir;
  std::map<std::string, Stage> m_stages;
};

}  // namespace thaw::pipeline
