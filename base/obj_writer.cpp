#include "base/obj_writer.h"

#include <array>
#include <charconv>
#include <system_error>

#include "base/atomic_file.h"
#include "base/check.h"

namespace thaw::meshio {

namespace {

// Appends `x` as printf's "%.<digits>g" would (std::to_chars with a precision is specified as that
// conversion, and is several times faster than glibc's printf: docs/benchmarks.md).
void append_general(std::string& out, double x, int digits) {
  char buf[40];
  const std::to_chars_result r =
      std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, digits);
  THAW_CHECK(r.ec == std::errc(), "a double fits 40 characters");
  out.append(buf, r.ptr);
}

void append_index(std::string& out, long long i) {
  char buf[24];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, i);
  out.append(buf, r.ptr);
}

void append_line(std::string& out, const char* tag, const std::array<double, 3>& v, int digits) {
  out += tag;
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    append_general(out, v[k], digits);
  }
  out += '\n';
}

}  // namespace

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  std::string out;
  format_obj(mesh, comment, out);
  return out;
}

void format_obj(const TriangleMesh& mesh, const std::string& comment, std::string& out) {
  const bool normals = !mesh.normal_triangles.empty();
  THAW_CHECK(!normals || mesh.normal_triangles.size() == mesh.triangles.size(),
             "one normal triple per triangle");
  out.clear();
  out.reserve(mesh.vertices.size() * 70 + mesh.normals.size() * 40 + mesh.triangles.size() * 40 +
              256);
  if (!comment.empty()) out += "# " + comment + "\n";
  // Vertices with 17 significant digits (they read back bit for bit), normals with 9.
  for (const auto& v : mesh.vertices) append_line(out, "v", v, 17);
  for (const auto& v : mesh.normals) append_line(out, "vn", v, 9);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    out += 'f';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      append_index(out, static_cast<long long>(t[c]) + 1);
      if (normals) {
        out += "//";
        append_index(out, static_cast<long long>(mesh.normal_triangles[f][c]) + 1);
      }
    }
    out += '\n';
  }
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

}  // namespace thaw::meshio
