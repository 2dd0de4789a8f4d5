#include "base/text_file.h"

#include <fstream>
#include <sstream>
#include <system_error>

#include "base/error.h"

namespace thaw {

namespace {
std::string mebibytes(std::uintmax_t bytes) {
  std::ostringstream os;
  os.precision(3);
  os << double(bytes) / double(1 << 20) << " MiB";
  return os.str();
}
}  // namespace

std::string read_text_file(const std::filesystem::path& path, const std::string& kind,
                           std::uintmax_t max_bytes) {
  const std::string name = path.string();
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found || name.empty())
    throw UserError(name, "", "no such file");
  if (ec) throw UserError(name, "", "cannot be read: " + ec.message());
  if (st.type() == std::filesystem::file_type::directory)
    throw UserError(name, "", "is a directory, expected " + kind);
  if (st.type() != std::filesystem::file_type::regular)
    throw UserError(name, "", "is not a regular file, expected " + kind);
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && max_bytes > 0 && size > max_bytes)
    throw UserError(name, "",
                    "is " + mebibytes(size) + ", more than the " + mebibytes(max_bytes) +
                        " accepted for " + kind);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(name, "", "cannot be read (permission denied?)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw UserError(name, "", "read error");
  return buffer.str();
}

}  // namespace thaw
