#pragma once
// Reading a whole input file into memory, with the checks every reader of user files shares:
// the file exists, is a regular file (a directory, a device such as /dev/zero or a named pipe is
// refused before it is opened: reading one could block or never end), is not larger than the
// caller's limit (a typo such as a 3 GB file given as a scenario is refused before any
// allocation), and reads without error. Problems are thaw::UserError naming the file.
// Knows nothing about the file's format.
#include <cstdint>
#include <filesystem>
#include <string>

namespace thaw {

/// Largest TOML file (scenario, scene, media) accepted: 64 MiB, 100x the largest spectral table
/// a user might paste in, far below what parsing it would cost in memory (toml++ uses ~10x).
inline constexpr std::uintmax_t kMaxTomlFileBytes = std::uintmax_t(64) << 20;

/// The contents of `path`. `kind` names what was expected in messages ("a TOML file", "an OBJ
/// file"). max_bytes = 0: no limit.
std::string read_text_file(const std::filesystem::path& path, const std::string& kind,
                           std::uintmax_t max_bytes = 0);

}  // namespace thaw
