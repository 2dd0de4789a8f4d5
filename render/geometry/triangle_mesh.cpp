#include "render/geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <unordered_map>

#include "base/error.h"

namespace thaw::render {

TriangleMesh from_file_mesh(const meshio::TriangleMesh& file, const std::string& source) {
  constexpr auto max_index = static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max());
  if (file.vertices.size() > max_index || file.normals.size() > max_index)
    throw UserError(source, "", "more than 2^32 - 1 vertices or normals (the renderer's limit)");
  TriangleMesh mesh;
  mesh.positions.reserve(file.vertices.size());
  for (const auto& v : file.vertices)
    mesh.positions.push_back(
        Vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])));
  mesh.triangles.reserve(file.triangles.size());
  for (const auto& t : file.triangles)
    mesh.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                              static_cast<std::uint32_t>(t[2])});
  for (std::size_t i = 0; i < file.normals.size(); ++i) {
    const auto& n = file.normals[i];
    const Vec3 v(static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]));
    const float len = length(v);
    if (!(len > 0.0f))
      throw UserError(source, "normal " + std::to_string(i + 1), "zero-length normal");
    mesh.normals.push_back(v / len);
  }
  for (const auto& t : file.normal_triangles)
    mesh.normal_indices.push_back({static_cast<std::uint32_t>(t[0]),
                                   static_cast<std::uint32_t>(t[1]),
                                   static_cast<std::uint32_t>(t[2])});
  // Coordinates finite in double can overflow float (1e39): the renderer's own check.
  if (auto problem = validate_mesh(mesh)) throw UserError(source, "", *problem);
  return mesh;
}

namespace {

bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Canonical vertex id per distinct position (so duplicated seam vertices count as one).
std::vector<std::uint32_t> weld_by_position(const TriangleMesh& mesh) {
  std::vector<std::uint32_t> order(mesh.positions.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3 &p = mesh.positions[a], &q = mesh.positions[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> canon(mesh.positions.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && mesh.positions[order[k]] == mesh.positions[order[k - 1]])
      canon[order[k]] = canon[order[k - 1]];
    else
      canon[order[k]] = order[k];
  }
  return canon;
}

}  // namespace

std::optional<std::string> validate_mesh(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return "mesh has no triangles";
  const auto nv = mesh.positions.size();
  for (std::size_t i = 0; i < nv; ++i)
    if (!finite(mesh.positions[i]))
      return "vertex " + std::to_string(i + 1) + " has a non-finite coordinate";
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (auto i : mesh.triangles[t])
      if (i >= nv)
        return "triangle " + std::to_string(t + 1) + " uses vertex index " + std::to_string(i + 1) +
               " but there are " + std::to_string(nv) + " vertices";
  if (mesh.has_normals()) {
    if (mesh.normal_indices.size() != mesh.triangles.size())
      return "normal indices do not match the triangle count";
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
      if (!finite(mesh.normals[i]) || !(length(mesh.normals[i]) > 0.0f))
        return "normal " + std::to_string(i + 1) + " is zero or non-finite";
    for (std::size_t t = 0; t < mesh.normal_indices.size(); ++t)
      for (auto i : mesh.normal_indices[t])
        if (i >= mesh.normals.size())
          return "triangle " + std::to_string(t + 1) + " uses normal index " +
                 std::to_string(i + 1) + " but there are " + std::to_string(mesh.normals.size()) +
                 " normals";
  }
  return std::nullopt;
}

std::optional<std::string> closed_surface_problem(const TriangleMesh& mesh) {
  const auto canon = weld_by_position(mesh);
  // Directed edge (a, b) -> number of uses; a closed oriented manifold uses each directed edge
  // once and its reverse once.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(mesh.triangles.size() * 3);
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const std::uint32_t v[3] = {canon[tri[0]], canon[tri[1]], canon[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      return "triangle " + std::to_string(t + 1) + " is degenerate (repeated vertex)";
    for (int e = 0; e < 3; ++e) {
      const int uses = ++directed[key(v[e], v[(e + 1) % 3])];
      if (uses > 1)
        return "edge used twice in the same direction at triangle " + std::to_string(t + 1) +
               " (inconsistent orientation or non-manifold)";
    }
  }
  for (const auto& [k, n] : directed) {
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k);
    if (!directed.count(key(b, a)))
      return "not closed: edge between vertices " + std::to_string(a + 1) + " and " +
             std::to_string(b + 1) + " has only one triangle";
  }
  return std::nullopt;
}

double signed_volume(const TriangleMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    // a . (b x c) / 6 in double
    const double bxc_x = double(b.y) * c.z - double(b.z) * c.y;
    const double bxc_y = double(b.z) * c.x - double(b.x) * c.z;
    const double bxc_z = double(b.x) * c.y - double(b.y) * c.x;
    v += a.x * bxc_x + a.y * bxc_y + a.z * bxc_z;
  }
  return v / 6.0;
}

void compute_smooth_normals(TriangleMesh& mesh) {
  const auto canon = weld_by_position(mesh);
  std::vector<Vec3> acc(mesh.positions.size(), Vec3{0, 0, 0});
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const Vec3 n = cross(b - a, c - a);  // |n| = twice the area: area weighting
    for (int k = 0; k < 3; ++k) acc[canon[t[k]]] += n;
  }
  mesh.normals.assign(mesh.positions.size(), Vec3{0, 0, 0});
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3 n = acc[canon[i]];
    const float len = length(n);
    mesh.normals[i] = len > 0.0f ? n / len : Vec3{0, 0, 1};
  }
  mesh.normal_indices = mesh.triangles;
}

void rotate_mesh(TriangleMesh& mesh, const std::array<double, 3>& degrees) {
  // R = Rz Ry Rx, each a right-handed turn about its axis.
  double r[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    const double a = degrees[std::size_t(axis)] * std::numbers::pi / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    double turn[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    turn[i][i] = c, turn[i][j] = -s, turn[j][i] = s, turn[j][j] = c;
    double next[3][3] = {};
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        for (int k = 0; k < 3; ++k) next[row][col] += turn[row][k] * r[k][col];
    std::copy(&next[0][0], &next[0][0] + 9, &r[0][0]);
  }
  const auto apply = [&](Vec3& v) {
    const double x = v.x, y = v.y, z = v.z;
    v = Vec3{float(r[0][0] * x + r[0][1] * y + r[0][2] * z),
             float(r[1][0] * x + r[1][1] * y + r[1][2] * z),
             float(r[2][0] * x + r[2][1] * y + r[2][2] * z)};
  };
  for (auto& p : mesh.positions) apply(p);
  for (auto& n : mesh.normals) apply(n);
}

void transform_mesh(TriangleMesh& mesh, double scale, const std::array<double, 3>& translate) {
  for (auto& p : mesh.positions)
    p = Vec3{static_cast<float>(scale * p.x + translate[0]),
             static_cast<float>(scale * p.y + translate[1]),
             static_cast<float>(scale * p.z + translate[2])};
}

}  // namespace thaw::render
