#pragma once
// Atomic outputs: everything thaw writes goes to a temporary name next to its destination and is
// renamed into place only when complete, so an interrupted run never leaves a half-written file
// (rename(2) is atomic within one file system). Knows nothing about what is written.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace thaw {

/// A unique temporary path beside `final_path` (same directory, so rename is atomic).
std::filesystem::path temporary_sibling(const std::filesystem::path& final_path);

/// Writes `contents` to `path` atomically; throws UserError naming the path on failure.
void write_file_atomic(const std::filesystem::path& path, std::string_view contents);

/// Removes, anywhere under `dir`, temporary files and folders left by thaw processes that no
/// longer exist or are zombies (a run killed while writing); those of live processes are kept.
/// Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& dir);

/// The name `path` will have once the staging folders (StagingDirectory) of this process holding
/// it are committed: what messages name, never a temporary. Other paths are returned as they are.
std::filesystem::path final_name(const std::filesystem::path& path);

/// Creates `dir` (and parents) or throws UserError naming it if that is impossible or it is a file.
void ensure_directory(const std::filesystem::path& dir);

/// A stream to a temporary file that becomes `path` on commit(); removed if never committed.
class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::filesystem::path path, bool binary = false);
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  ~AtomicOutputFile();

  std::ofstream& stream() { return m_stream; }
  /// Flushes, checks the stream and renames into place; throws UserError on any failure.
  void commit();

 private:
  std::filesystem::path m_path, m_temp;
  std::ofstream m_stream;
  bool m_committed = false;
};

/// A directory that is filled under a temporary name and replaces `final_dir` on commit(), so a
/// reader never sees a half-filled result folder. Removed if never committed.
class StagingDirectory {
 public:
  explicit StagingDirectory(std::filesystem::path final_dir);
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  ~StagingDirectory();

  const std::filesystem::path& path() const { return m_temp; }
  /// Replaces final_dir (an existing one is moved aside, then deleted) with the staged folder.
  void commit();

 private:
  std::filesystem::path m_final, m_temp;
  bool m_committed = false;
};

}  // namespace thaw
