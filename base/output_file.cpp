#include "base/output_file.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include "base/error.h"

namespace thaw {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void check_output_file(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> extensions) {
  const std::string ext = lower_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string expected;
    std::size_t i = 0;
    for (std::string_view e : extensions) {
      if (i > 0) expected += i + 1 == extensions.size() ? " or " : ", ";
      expected += e;
      ++i;
    }
    throw UserError(path.string(), "",
                    "unsupported output format '" + ext + "' (expected " + expected + ")");
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw UserError(path.string(), "", "is a directory");
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw UserError(path.string(), "", "'" + dir.string() + "' is not a directory");
}

}  // namespace thaw
