#include "sim/shape/obj_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "src/common/error.h"

namespace thaw::sim {

namespace {

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const V3& a) {
  return std::sqrt(dot(a, a));
}

/// Squared distance from p to triangle abc (Ericson, "Real-Time Collision Detection", 5.1.5).
double triangle_distance2(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2_to = [&](const V3& q) {
    const V3 d = sub(p, q);
    return dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0) return d2_to(a);
  const V3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return d2_to(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return d2_to({a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]});
  }
  const V3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return d2_to(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return d2_to({a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return d2_to({b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])});
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return d2_to(
      {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}

/// Solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983), signed.
double solid_angle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 x = sub(a, p), y = sub(b, p), z = sub(c, p);
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
  return 2 * std::atan2(num, den);
}

}  // namespace

double ObjMesh::signed_distance(const V3& p) const {
  double best = std::numeric_limits<double>::infinity(), winding = 0;
  for (const auto& t : triangles) {
    const V3 &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    best = std::min(best, triangle_distance2(p, a, b, c));
    winding += solid_angle(p, a, b, c);
  }
  const double d = std::sqrt(best);
  return winding / (4 * std::numbers::pi) > 0.5 ? -d : d;
}

double ObjMesh::volume() const {
  double v = 0;
  for (const auto& t : triangles) v += dot(vertices[t[0]], cross(vertices[t[1]], vertices[t[2]]));
  return v / 6;
}

ObjMesh read_obj_mesh(const std::filesystem::path& file, double scale, const V3& translate_m,
                      const std::string& scenario, const std::string& key) {
  const std::string name = file.string();
  auto fail = [&](const std::string& problem) {
    throw UserError(scenario, key, "OBJ file '" + name + "': " + problem);
  };
  std::ifstream in(file);
  if (!in) fail(std::filesystem::exists(file) ? "cannot be read" : "file not found");
  ObjMesh mesh;
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag) || tag[0] == '#') continue;
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (tag == "v") {
      V3 v{};
      for (double& x : v)
        if (!(ls >> x) || !std::isfinite(x))
          fail(where + "a vertex needs three finite coordinates");
      mesh.vertices.push_back({v[0] * scale + translate_m[0], v[1] * scale + translate_m[1],
                               v[2] * scale + translate_m[2]});
    } else if (tag == "f") {
      std::vector<int> face;
      std::string token;
      while (ls >> token) {
        const std::string index = token.substr(0, token.find('/'));
        char* end = nullptr;
        const long i = std::strtol(index.c_str(), &end, 10);
        const long count = static_cast<long>(mesh.vertices.size());
        if (index.empty() || *end != '\0' || i == 0 || i > count || i < -count)
          fail(where + "bad vertex index '" + token + "'");
        face.push_back(static_cast<int>(i > 0 ? i - 1 : count + i));
      }
      if (face.size() < 3) fail(where + "a face needs at least three vertices");
      for (std::size_t k = 1; k + 1 < face.size(); ++k) {
        const std::array<int, 3> t{face[0], face[k], face[k + 1]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
          fail(where + "degenerate face (repeated vertex)");
        mesh.triangles.push_back(t);
      }
    }
  }
  if (mesh.triangles.size() < 4)
    fail("needs a closed surface (at least 4 triangles), found " +
         std::to_string(mesh.triangles.size()));
  // Closed, edge-manifold and consistently oriented: every directed edge exactly once, and its
  // reverse exactly once.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    if (count > 1)
      fail("not manifold or inconsistently oriented: edge " + std::to_string(edge.first + 1) + "-" +
           std::to_string(edge.second + 1) + " is used " + std::to_string(count) +
           " times in the same direction");
    const auto rev = directed.find({edge.second, edge.first});
    if (rev == directed.end())
      fail("not closed: edge " + std::to_string(edge.first + 1) + "-" +
           std::to_string(edge.second + 1) + " borders only one face");
  }
  const double v = mesh.volume();
  if (!(v > 0))
    fail(
        "encloses a negative or zero volume: faces must be ordered counter-clockwise seen from "
        "outside");
  mesh.lower = mesh.upper = mesh.vertices[mesh.triangles[0][0]];
  for (const auto& t : mesh.triangles)
    for (int i : t)
      for (int a = 0; a < 3; ++a) {
        mesh.lower[a] = std::min(mesh.lower[a], mesh.vertices[i][a]);
        mesh.upper[a] = std::max(mesh.upper[a], mesh.vertices[i][a]);
      }
  return mesh;
}

}  // namespace thaw::sim
