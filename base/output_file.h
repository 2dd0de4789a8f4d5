#pragma once
// The checks every command makes on an output file's name before any work starts, so a typo
// never costs a run and never overwrites the wrong file: a known extension (any case), not a
// folder, and a folder to go in that is one (a missing folder is the caller's to refuse or
// create). Problems are thaw::UserError naming the path. Knows nothing about the formats.
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace thaw {

/// The extension of `path` in lower case, with its dot (".png"), or "".
std::string lower_extension(const std::filesystem::path& path);

/// Throws UserError(path, "", problem) when `path`'s extension is none of `extensions` (".png";
/// "unsupported output format '.jpg' (expected .png, .pfm or .exr)"), when it is a folder, or
/// when its parent exists but is not a folder.
void check_output_file(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> extensions);

}  // namespace thaw
