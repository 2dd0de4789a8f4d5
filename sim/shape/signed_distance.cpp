#include "sim/shape/signed_distance.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/check.h"

namespace thaw::sim {

const char* to_string(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::box:
      return "box";
    case ShapeKind::sphere:
      return "sphere";
    case ShapeKind::cylinder:
      return "cylinder";
    case ShapeKind::obj:
      return "obj";
  }
  return "?";
}

SignedDistance::SignedDistance(const ShapeSpec& spec, std::shared_ptr<const ObjMesh> mesh)
    : m_spec(spec), m_mesh(std::move(mesh)) {
  THAW_CHECK(spec.kind != ShapeKind::obj || m_mesh, "an OBJ shape needs its mesh");
}

double SignedDistance::operator()(const std::array<double, 3>& p) const {
  const auto& c = m_spec.center_m;
  const double x = p[0] - c[0], y = p[1] - c[1], z = p[2] - c[2];
  switch (m_spec.kind) {
    case ShapeKind::sphere:
      return std::sqrt(x * x + y * y + z * z) - m_spec.radius_m;
    case ShapeKind::box: {
      // rounded box (Quilez): the box shrunk by the edge radius, inflated by it
      const double r = m_spec.edge_radius_m;
      const double q[3] = {std::abs(x) - (0.5 * m_spec.size_m[0] - r),
                           std::abs(y) - (0.5 * m_spec.size_m[1] - r),
                           std::abs(z) - (0.5 * m_spec.size_m[2] - r)};
      double outside = 0;
      for (double v : q) outside += std::max(v, 0.0) * std::max(v, 0.0);
      return std::sqrt(outside) + std::min(std::max({q[0], q[1], q[2]}), 0.0) - r;
    }
    case ShapeKind::cylinder: {
      const double q[2] = {std::sqrt(x * x + z * z) - m_spec.radius_m,
                           std::abs(y) - 0.5 * m_spec.height_m};
      const double ox = std::max(q[0], 0.0), oy = std::max(q[1], 0.0);
      return std::sqrt(ox * ox + oy * oy) + std::min(std::max(q[0], q[1]), 0.0);
    }
    case ShapeKind::obj:
      return m_mesh->signed_distance(p);
  }
  return 0;
}

std::array<double, 3> SignedDistance::lower() const {
  const auto& c = m_spec.center_m;
  switch (m_spec.kind) {
    case ShapeKind::sphere:
      return {c[0] - m_spec.radius_m, c[1] - m_spec.radius_m, c[2] - m_spec.radius_m};
    case ShapeKind::box:
      return {c[0] - 0.5 * m_spec.size_m[0], c[1] - 0.5 * m_spec.size_m[1],
              c[2] - 0.5 * m_spec.size_m[2]};
    case ShapeKind::cylinder:
      return {c[0] - m_spec.radius_m, c[1] - 0.5 * m_spec.height_m, c[2] - m_spec.radius_m};
    case ShapeKind::obj:
      return m_mesh->lower;
  }
  return c;
}

std::array<double, 3> SignedDistance::upper() const {
  const auto& c = m_spec.center_m;
  switch (m_spec.kind) {
    case ShapeKind::sphere:
      return {c[0] + m_spec.radius_m, c[1] + m_spec.radius_m, c[2] + m_spec.radius_m};
    case ShapeKind::box:
      return {c[0] + 0.5 * m_spec.size_m[0], c[1] + 0.5 * m_spec.size_m[1],
              c[2] + 0.5 * m_spec.size_m[2]};
    case ShapeKind::cylinder:
      return {c[0] + m_spec.radius_m, c[1] + 0.5 * m_spec.height_m, c[2] + m_spec.radius_m};
    case ShapeKind::obj:
      return m_mesh->upper;
  }
  return c;
}

std::vector<std::array<double, 3>> SignedDistance::surface_samples(int count) const {
  std::vector<std::array<double, 3>> out;
  const auto& c = m_spec.center_m;
  const double pi = std::numbers::pi;
  switch (m_spec.kind) {
    case ShapeKind::sphere:
      // Fibonacci lattice plus the six poles
      for (int i = 0; i < count; ++i) {
        const double yy = 1 - 2 * (i + 0.5) / count, rr = std::sqrt(1 - yy * yy),
                     phi = i * pi * (3 - std::sqrt(5.0));
        out.push_back({c[0] + m_spec.radius_m * rr * std::cos(phi), c[1] + m_spec.radius_m * yy,
                       c[2] + m_spec.radius_m * rr * std::sin(phi)});
      }
      for (int a = 0; a < 3; ++a)
        for (double sgn : {-1.0, 1.0}) {
          auto q = c;
          q[a] += sgn * m_spec.radius_m;
          out.push_back(q);
        }
      break;
    case ShapeKind::box: {
      // a lattice on each face (edges and corners included), pushed onto the rounded surface
      const int g = std::max(2, static_cast<int>(std::sqrt(count / 6.0)));
      const double r = m_spec.edge_radius_m;
      for (int a = 0; a < 3; ++a)
        for (double sgn : {-1.0, 1.0})
          for (int u = 0; u <= g; ++u)
            for (int v = 0; v <= g; ++v) {
              std::array<double, 3> q{};
              const int b = (a + 1) % 3, d = (a + 2) % 3;
              q[a] = sgn * 0.5 * m_spec.size_m[a];
              q[b] = (-0.5 + static_cast<double>(u) / g) * m_spec.size_m[b];
              q[d] = (-0.5 + static_cast<double>(v) / g) * m_spec.size_m[d];
              std::array<double, 3> inner{}, dir{};
              double len = 0;
              for (int e = 0; e < 3; ++e) {
                const double hlf = 0.5 * m_spec.size_m[e] - r;
                inner[e] = std::clamp(q[e], -hlf, hlf);
                dir[e] = q[e] - inner[e];
                len += dir[e] * dir[e];
              }
              len = std::sqrt(len);
              std::array<double, 3> s{};
              for (int e = 0; e < 3; ++e)
                s[e] = c[e] + (len > 0 && r > 0 ? inner[e] + r * dir[e] / len : q[e]);
              out.push_back(s);
            }
      break;
    }
    case ShapeKind::cylinder: {
      const int g = std::max(8, static_cast<int>(std::sqrt(count / 3.0)));
      for (int u = 0; u < 2 * g; ++u) {
        const double phi = pi * u / g, cs = std::cos(phi), sn = std::sin(phi);
        for (int v = 0; v <= g; ++v) {
          const double yy = (-0.5 + static_cast<double>(v) / g) * m_spec.height_m;
          out.push_back({c[0] + m_spec.radius_m * cs, c[1] + yy, c[2] + m_spec.radius_m * sn});
        }
        for (int v = 0; v < g; ++v)
          for (double sgn : {-1.0, 1.0}) {
            const double rr = m_spec.radius_m * v / g;
            out.push_back({c[0] + rr * cs, c[1] + sgn * 0.5 * m_spec.height_m, c[2] + rr * sn});
          }
      }
      break;
    }
    case ShapeKind::obj:
      for (const auto& v : m_mesh->vertices) out.push_back(v);
      for (const auto& t : m_mesh->triangles) {
        const auto &a = m_mesh->vertices[t[0]], &b = m_mesh->vertices[t[1]],
                   &d = m_mesh->vertices[t[2]];
        out.push_back(
            {(a[0] + b[0] + d[0]) / 3, (a[1] + b[1] + d[1]) / 3, (a[2] + b[2] + d[2]) / 3});
        for (int e = 0; e < 3; ++e) {
          const auto& p0 = m_mesh->vertices[t[e]];
          const auto& p1 = m_mesh->vertices[t[(e + 1) % 3]];
          out.push_back({0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), 0.5 * (p0[2] + p1[2])});
        }
      }
      break;
  }
  return out;
}

}  // namespace thaw::sim
