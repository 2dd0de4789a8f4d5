#pragma once
// Shared by the libFuzzer targets: the input as text, and the same input as a file (for the
// readers whose interface is a path: interfaces.csv, summary.json). Every target accepts
// thaw::UserError (bad input answered as promised); anything else (another exception, a crash, a
// sanitizer report, a hang) is a finding. Header-only, no test framework.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace thaw::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Writes the input to one file per process under /dev/shm (or the temp folder) and returns it.
inline const std::filesystem::path& as_file(const std::uint8_t* data, std::size_t size,
                                            const std::string& name) {
  static const std::filesystem::path dir = [] {
    std::filesystem::path base = std::filesystem::is_directory("/dev/shm")
                                     ? std::filesystem::path("/dev/shm")
                                     : std::filesystem::temp_directory_path();
    base /= "thaw-fuzz-" + std::to_string(::getpid());
    std::filesystem::create_directories(base);
    return base;
  }();
  static std::filesystem::path file;
  file = dir / name;
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace thaw::fuzz
