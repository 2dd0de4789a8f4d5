#include "base/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "base/error.h"

namespace thaw {
namespace fs = std::filesystem;

fs::path temporary_sibling(const fs::path& final_path) {
  static std::atomic<unsigned> counter{0};
  fs::path p = final_path;
  p += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return p;
}

namespace {

// The process id in a temporary_sibling() name, <final>.tmp-<pid>-<counter> with both numbers
// plain decimal digits to the end of the name, or 0 for any other name (a user's "notes.tmp-old"
// is not thaw's and is never removed).
long temporary_owner(const std::string& name) {
  const auto pos = name.rfind(".tmp-");
  if (pos == std::string::npos) return 0;
  const std::string tail = name.substr(pos + 5);
  const auto dash = tail.find('-');
  const auto digits = [](std::string_view s) {
    return !s.empty() && s.size() <= 18 &&
           s.find_first_not_of("0123456789") == std::string_view::npos;
  };
  if (dash == std::string::npos || !digits(std::string_view(tail).substr(0, dash)) ||
      !digits(std::string_view(tail).substr(dash + 1)))
    return 0;
  return std::strtol(tail.c_str(), nullptr, 10);
}

// The live staging folders of this process, (temporary, final), for final_name().
std::mutex g_staging_mutex;
std::vector<std::pair<fs::path, fs::path>>& live_stagings() {
  static std::vector<std::pair<fs::path, fs::path>> list;
  return list;
}

void remember_staging(const fs::path& temp, const fs::path& final_dir) {
  const std::lock_guard<std::mutex> lock(g_staging_mutex);
  live_stagings().emplace_back(temp, final_dir);
}

void forget_staging(const fs::path& temp) {
  const std::lock_guard<std::mutex> lock(g_staging_mutex);
  std::erase_if(live_stagings(), [&](const auto& e) { return e.first == temp; });
}

// An error about `path` (being written), named as it will be once committed.
UserError write_error(const fs::path& path, const std::string& problem) {
  return UserError(final_name(path).string(), "", problem);
}

}  // namespace

fs::path final_name(const fs::path& path) {
  const std::lock_guard<std::mutex> lock(g_staging_mutex);
  fs::path p = path;
  // Innermost first: a staging folder may be created inside another one's temporary.
  for (auto it = live_stagings().rbegin(); it != live_stagings().rend(); ++it) {
    const auto [temp_end, path_end] =
        std::mismatch(it->first.begin(), it->first.end(), p.begin(), p.end());
    if (temp_end != it->first.end()) continue;
    fs::path renamed = it->second;
    for (auto c = path_end; c != p.end(); ++c) renamed /= *c;
    p = renamed;
  }
  return p;
}

namespace {

// Whether process `pid` can still write: it exists and is not a zombie. A killed process stays a
// zombie until its parent reaps it; under mpirun killed first, a rank's parent is init, and in a
// container init may never reap it, so its temporaries would be kept for good (Linux's
// /proc/PID/stat: the state after the parenthesised command name, 'Z' for a zombie).
bool can_still_write(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;  // no /proc: trust kill()
  const auto paren = line.rfind(')');
  return !(paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] == 'Z');
}

}  // namespace

int remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const long pid = temporary_owner(it->path().filename().string());
    if (pid > 0 && !can_still_write(pid)) {
      stale.push_back(it->path());
      if (it->is_directory(ec)) it.disable_recursion_pending();
    }
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
  return static_cast<int>(stale.size());
}

void ensure_directory(const fs::path& dir) {
  if (dir.empty()) return;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw write_error(dir, "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw write_error(dir, "cannot create directory: " + ec.message());
}

void write_file_atomic(const fs::path& path, std::string_view contents) {
  AtomicOutputFile out(path, true);
  out.stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
  out.commit();
}

AtomicOutputFile::AtomicOutputFile(fs::path path, bool binary)
    : m_path(std::move(path)), m_temp(temporary_sibling(m_path)) {
  m_stream.open(m_temp, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!m_stream) throw write_error(m_path, std::string("cannot write: ") + std::strerror(errno));
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!m_committed) {
    m_stream.close();
    std::error_code ec;
    fs::remove(m_temp, ec);
  }
}

void AtomicOutputFile::commit() {
  m_stream.flush();
  const bool ok = static_cast<bool>(m_stream);
  m_stream.close();
  if (!ok || m_stream.fail()) {
    std::error_code ec;
    fs::remove(m_temp, ec);
    m_committed = true;
    throw write_error(m_path, "write failed (disk full or I/O error)");
  }
  std::error_code ec;
  fs::rename(m_temp, m_path, ec);
  m_committed = true;
  if (ec) {
    fs::remove(m_temp, ec);
    throw write_error(m_path, "cannot rename temporary file into place: " + ec.message());
  }
}

StagingDirectory::StagingDirectory(fs::path final_dir)
    : m_final(std::move(final_dir)), m_temp(temporary_sibling(m_final)) {
  if (m_final.has_parent_path()) ensure_directory(m_final.parent_path());
  std::error_code ec;
  if (fs::exists(m_final, ec) && !fs::is_directory(m_final, ec))
    throw UserError(m_final.string(), "", "exists and is not a directory");
  fs::create_directories(m_temp, ec);
  if (ec) throw UserError(m_final.string(), "", "cannot create output directory: " + ec.message());
  remember_staging(m_temp, m_final);
}

StagingDirectory::~StagingDirectory() {
  forget_staging(m_temp);
  if (!m_committed) {
    std::error_code ec;
    fs::remove_all(m_temp, ec);
  }
}

void StagingDirectory::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(m_final, ec)) {
    old = temporary_sibling(m_final);
    fs::rename(m_final, old, ec);
    if (ec)
      throw UserError(m_final.string(), "", "cannot replace existing output: " + ec.message());
  }
  fs::rename(m_temp, m_final, ec);
  if (ec) throw UserError(m_final.string(), "", "cannot move output into place: " + ec.message());
  m_committed = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace thaw
