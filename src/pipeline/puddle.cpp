#include "src/pipeline/puddle.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/check.h"

namespace thaw::pipeline {
namespace {

constexpr double kPi = std::numbers::pi;

/// Integrals over y in [0, h] of the inner wall's d and d^2 (closed forms: the ice surface's
/// section is a circle of radius r about the core's lowest part, u = c - y below it).
struct WallIntegrals {
  double d = 0, d2 = 0;
};

WallIntegrals wall_integrals(const PuddleShape& s, double h) {
  if (!s.ice) return {};
  // The wall is the surface at distance r + gap from the core: its section is a circle of that
  // radius about the core's lowest part, u = c - y below it, and it is that wide above.
  const double r = s.ice->radius_m + s.ice_gap_m, c = s.ice->core_bottom_y - s.floor_y;
  const auto clamp_u = [&](double u) { return std::clamp(u, 0.0, r); };
  // antiderivatives in u of sqrt(r^2 - u^2) and r^2 - u^2 on [0, r]
  const auto f = [&](double u) {
    return 0.5 * (u * std::sqrt(std::max(0.0, r * r - u * u)) + r * r * std::asin(u / r));
  };
  const auto f2 = [&](double u) { return r * r * u - u * u * u / 3.0; };
  const double above_core = std::max(0.0, h - std::max(0.0, c));
  return {f(clamp_u(c)) - f(clamp_u(c - h)) + r * above_core,
          f2(clamp_u(c)) - f2(clamp_u(c - h)) + r * r * above_core};
}

/// The rim under its arc: the region d >= R, 0 <= y <= h inside the circle of radius rho about
/// (R, h - rho): its area and the integral of its width squared over y (closed forms).
struct RimIntegrals {
  double area = 0, width2 = 0;
};

double rim_radius(double h, double contact_angle_rad) {
  return h / (1 - std::cos(contact_angle_rad));
}

RimIntegrals rim_integrals(double h, double contact_angle_rad) {
  const double rho = rim_radius(h, contact_angle_rad);
  const auto f = [&](double u) {
    return 0.5 * (u * std::sqrt(std::max(0.0, rho * rho - u * u)) +
                  rho * rho * std::asin(std::clamp(u / rho, -1.0, 1.0)));
  };
  const auto f2 = [&](double u) { return rho * rho * u - u * u * u / 3.0; };
  // u = y - (h - rho) runs over [rho - h, rho]
  return {f(rho) - f(rho - h), f2(rho) - f2(rho - h)};
}

/// Water volume of the profile {0 <= y <= h, wall(y) <= d <= R} plus the rim, swept round the
/// stadium outline (Steiner: V = 4 L A + 2 pi M, A the profile's area and M = int d dA).
struct VolumeQuadratic {
  double a2 = 0, a1 = 0, a0 = 0;  ///< V(R) = a2 R^2 + a1 R + a0
  double at(double r) const { return (a2 * r + a1) * r + a0; }
};

VolumeQuadratic volume_in_r(const PuddleShape& s, double h) {
  const double l = s.half_length_m;
  const WallIntegrals w = wall_integrals(s, h);
  const RimIntegrals rim = rim_integrals(h, s.contact_angle_rad);
  // A = R h - w.d + rim.area;  M = (R^2 h - w.d2) / 2 + R rim.area + rim.width2 / 2
  VolumeQuadratic q;
  q.a2 = kPi * h;
  q.a1 = 4 * l * h + 2 * kPi * rim.area;
  q.a0 = 4 * l * (rim.area - w.d) - kPi * w.d2 + kPi * rim.width2;
  return q;
}

}  // namespace

double PuddleShape::inner_wall_d(double y) const {
  if (!ice) return 0.0;
  const double r = ice->radius_m + ice_gap_m, u = ice->core_bottom_y - floor_y - y;
  if (u <= 0) return r;
  return std::sqrt(std::max(0.0, r * r - u * u));
}

double PuddleShape::volume_m3() const {
  return volume_in_r(*this, thickness_m).at(outer_offset_m);
}

PuddleShape make_puddle_shape(double volume_m3, double floor_y, double center_x, double center_z,
                              double half_length_m, const std::optional<IceFootprint>& ice,
                              const PuddleSettings& settings) {
  THAW_CHECK(volume_m3 > 0 && settings.thickness_m > 0, "a puddle needs water and a height");
  THAW_CHECK(!ice || ice->core_bottom_y - floor_y <= ice->radius_m + 0.5 * settings.ice_gap_m,
             "the ice must rest on the floor");
  PuddleShape s;
  s.floor_y = floor_y;
  s.center_x = center_x;
  s.center_z = center_z;
  s.ice = ice;
  s.ice_gap_m = ice ? settings.ice_gap_m : 0.0;
  THAW_CHECK(settings.contact_angle_deg > 0 && settings.contact_angle_deg < 180,
             "contact angle in (0, 180)");
  s.contact_angle_rad = settings.contact_angle_deg * kPi / 180.0;
  // Without ice the outline is a disc (its centre line would otherwise be a degenerate ring).
  s.half_length_m = ice ? half_length_m : 0.0;
  const auto zero_width_volume = [&](double h) { return volume_in_r(s, h).at(s.inner_wall_d(h)); };
  double h = settings.thickness_m;
  if (zero_width_volume(h) > volume_m3) {
    // Too little water for the full height: the thinner puddle of zero top width holds it
    // (its volume grows with h: the profile region of a larger h contains the smaller one's).
    double lo = 0, hi = h;
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i)
      (zero_width_volume(0.5 * (lo + hi)) > volume_m3 ? hi : lo) = 0.5 * (lo + hi);
    h = 0.5 * (lo + hi);
  }
  s.thickness_m = h;
  s.rim_radius_m = rim_radius(h, s.contact_angle_rad);
  const VolumeQuadratic q = volume_in_r(s, h);
  const double disc = q.a1 * q.a1 - 4 * q.a2 * (q.a0 - volume_m3);
  const double root = (-q.a1 + std::sqrt(std::max(0.0, disc))) / (2 * q.a2);
  s.outer_offset_m = std::max(root, s.inner_wall_d(h));
  return s;
}

namespace {

/// Appends q unless it repeats the last point (a puddle of nearly zero top width), keeping a
/// crease. Points closer than 0.1 um would coincide once the mesh's vertices are rounded to
/// float (1 ulp is 7 nm at 0.1 m), leaving degenerate facets.
void push_distinct(std::vector<ProfilePoint>& p, const ProfilePoint& q) {
  if (std::abs(p.back().d - q.d) < 1e-7 && std::abs(p.back().y - q.y) < 1e-7) {
    p.back().crease = p.back().crease || q.crease;
    return;
  }
  p.push_back(q);
}

}  // namespace

std::vector<ProfilePoint> PuddleShape::profile(const PuddleSettings& st) const {
  const double h = thickness_m, big_r = outer_offset_m, rho = rim_radius_m;
  const double t_floor = 0.5 * kPi - contact_angle_rad;  // the arc's angle at the floor
  const double contact_d = big_r + rho * std::cos(t_floor);
  std::vector<ProfilePoint> p;
  p.push_back({inner_wall_d(0), -st.sink_m, true});
  p.push_back({contact_d, -st.sink_m, true});
  p.push_back({contact_d, 0.0, true});
  for (int k = 1; k < st.rim_segments; ++k) {
    const double t = t_floor + (0.5 * kPi - t_floor) * k / st.rim_segments;
    push_distinct(p, {big_r + rho * std::cos(t), h - rho + rho * std::sin(t)});
  }
  push_distinct(p, {big_r, h});
  if (!ice) {
    push_distinct(p, {0.0, h});
    return p;
  }
  // The inner wall from the top down: chords of the ice's circular section (uniform in the
  // angle phi from its lowest point, u = r cos phi), plus the wall's corners.
  const double r = ice->radius_m + ice_gap_m, c = ice->core_bottom_y - floor_y;
  std::vector<double> ys{h, 0.0};
  const double phi_lo = std::acos(std::clamp(c / r, -1.0, 1.0));
  const double phi_hi = std::acos(std::clamp((c - h) / r, 0.0, 1.0));
  for (int k = 0; k <= st.wall_segments && phi_hi > phi_lo; ++k)
    ys.push_back(c - r * std::cos(phi_lo + (phi_hi - phi_lo) * k / st.wall_segments));
  std::sort(ys.begin(), ys.end(), std::greater<>());
  double last = h + 1;
  for (double y : ys) {
    y = std::clamp(y, 0.0, h);
    if (last - y < 1e-12) continue;
    push_distinct(p, {inner_wall_d(y), y, y == h || y == 0.0});
    last = y;
  }
  return p;
}

namespace {

/// Outward unit normal in (d, y) of the profile edge from a to b (counter-clockwise profile).
ProfilePoint edge_normal(const ProfilePoint& a, const ProfilePoint& b) {
  const double dd = b.d - a.d, dy = b.y - a.y, len = std::hypot(dd, dy);
  return {dy / len, -dd / len};
}

}  // namespace

render::TriangleMesh puddle_mesh(const PuddleShape& s, const PuddleSettings& st) {
  const std::vector<ProfilePoint> profile = s.profile(st);
  const std::size_t n_prof = profile.size();
  const bool closed = static_cast<bool>(s.ice);
  const std::size_t edges = closed ? n_prof : n_prof - 1;
  const int m = st.outline_segments;
  const double l = s.half_length_m;
  // Outline: a half circle round each end of the segment (z = +l, then z = -l), psi increasing
  // (x = cos psi, z = sin psi); a disc (l = 0) shares the ends' end points.
  struct OutlinePoint {
    double c, sn, z;
  };
  std::vector<OutlinePoint> outline;
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k <= m; ++k) {
      if (l == 0 && k == m) continue;
      const double psi = kPi * end + kPi * k / m;
      outline.push_back({std::cos(psi), std::sin(psi), end == 0 ? l : -l});
    }
  const std::size_t n_out = outline.size();
  render::TriangleMesh mesh;
  std::vector<std::uint32_t> ring_start;
  std::vector<bool> pole;
  for (const ProfilePoint& q : profile) {
    ring_start.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
    const float y = static_cast<float>(s.floor_y + q.y);
    pole.push_back(q.d < 1e-7 && l == 0);  // on the axis, to float resolution
    if (pole.back()) {
      mesh.positions.push_back({static_cast<float>(s.center_x), y, static_cast<float>(s.center_z)});
      continue;
    }
    for (const OutlinePoint& o : outline)
      mesh.positions.push_back({static_cast<float>(s.center_x + q.d * o.c), y,
                                static_cast<float>(s.center_z + o.z + q.d * o.sn)});
  }
  // Shading normals: per profile vertex and side (0 = end of the edge before it, 1 = start of
  // the edge after it) the edge's own normal at creases and the average of both edges elsewhere
  // (the arcs then shade smooth), turned round the outline.
  std::vector<ProfilePoint> side_normal(2 * n_prof);
  for (std::size_t i = 0; i < n_prof; ++i) {
    const bool has_before = closed || i > 0, has_after = closed || i + 1 < n_prof;
    const ProfilePoint before =
        has_before ? edge_normal(profile[(i + n_prof - 1) % n_prof], profile[i]) : ProfilePoint{};
    const ProfilePoint after =
        has_after ? edge_normal(profile[i], profile[(i + 1) % n_prof]) : ProfilePoint{};
    const double turn_cos = before.d * after.d + before.y * after.y;
    const bool crease =
        profile[i].crease || !has_before || !has_after || turn_cos < std::cos(20.0 * kPi / 180.0);
    if (crease) {
      side_normal[2 * i] = has_before ? before : after;  // an unused side repeats the used one
      side_normal[2 * i + 1] = has_after ? after : before;
    } else {
      const double nd = before.d + after.d, ny = before.y + after.y, len = std::hypot(nd, ny);
      side_normal[2 * i] = side_normal[2 * i + 1] = {nd / len, ny / len};
    }
  }
  for (const ProfilePoint& n : side_normal)
    for (const OutlinePoint& o : outline)
      mesh.normals.push_back(
          {static_cast<float>(n.d * o.c), static_cast<float>(n.y), static_cast<float>(n.d * o.sn)});
  const auto vertex = [&](std::size_t i, std::size_t j) {
    return ring_start[i] + (pole[i] ? 0 : static_cast<std::uint32_t>(j % n_out));
  };
  const auto normal = [&](std::size_t i, int side, std::size_t j) {
    return static_cast<std::uint32_t>((2 * i + side) * n_out + j % n_out);
  };
  // A triangle is skipped when two of its corners are the same point in float: profile points
  // distinct in double can round together (a puddle of zero top width: R - wall(h) ~ 1e-12 m,
  // far below float's 7e-9 m at 0.1 m). The strip's neighbours then share those positions, so
  // the surface stays closed once welded by position, as the renderer's checks weld it.
  const auto same = [&](std::uint32_t a, std::uint32_t b) {
    const auto &p = mesh.positions[a], &q = mesh.positions[b];
    return p.x == q.x && p.y == q.y && p.z == q.z;
  };
  const auto add = [&](std::array<std::uint32_t, 3> v, std::array<std::uint32_t, 3> n) {
    if (!same(v[0], v[1]) && !same(v[1], v[2]) && !same(v[0], v[2])) {
      mesh.triangles.push_back(v);
      mesh.normal_indices.push_back(n);
    }
  };
  // Profile counter-clockwise in (d, y), outline with psi increasing: the triangle (i, j),
  // (i+1, j), (i+1, j+1) has normal (dd n + dy y) x t = dy n - dd y, which points out.
  for (std::size_t i = 0; i < edges; ++i) {
    const std::size_t i1 = (i + 1) % n_prof;
    for (std::size_t j = 0; j < n_out; ++j) {
      add({vertex(i, j), vertex(i1, j), vertex(i1, j + 1)},
          {normal(i, 1, j), normal(i1, 0, j), normal(i1, 0, j + 1)});
      add({vertex(i, j), vertex(i1, j + 1), vertex(i, j + 1)},
          {normal(i, 1, j), normal(i1, 0, j + 1), normal(i, 1, j + 1)});
    }
  }
  return mesh;
}

double mesh_volume_above(const render::TriangleMesh& mesh, double floor_y) {
  double v = 0;
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.positions[t[0]];
    const auto& b = mesh.positions[t[1]];
    const auto& c = mesh.positions[t[2]];
    const double ya = a.y - floor_y, yb = b.y - floor_y, yc = c.y - floor_y;
    // y component of (b - a) x (c - a), in double
    const double ny =
        (double(b.z) - a.z) * (double(c.x) - a.x) - (double(b.x) - a.x) * (double(c.z) - a.z);
    v += (std::max(ya, 0.0) + std::max(yb, 0.0) + std::max(yc, 0.0)) / 3.0 * ny * 0.5;
  }
  return v;
}

}  // namespace thaw::pipeline
