#include "src/inspect/field_line.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "base/error.h"
#include "base/number_text.h"

namespace thaw::inspect {
namespace fs = std::filesystem;
namespace {

const char* const kKey = "--over-line";

/// Position of `x` among the centres of `n` cells of edge h from `origin`: the lower centre's
/// index and the weight of the upper one, held at the outermost centres.
struct Bracket {
  int lo = 0;
  double w = 0;
};
Bracket bracket(double x, double origin, double h, int n) {
  const double s = (x - origin) / h - 0.5;
  if (n == 1 || s <= 0) return {0, 0.0};
  if (s >= n - 1) return {n - 2, 1.0};
  const int lo = static_cast<int>(std::floor(s));
  return {lo, s - lo};
}

/// The point's coordinate along axis `axis` of the grid's box, or a UserError naming the box.
/// Round-off of a point typed on the border (1e-9 of a cell) is taken as on it.
void check_inside(double x, double lo, double hi, double h, char axis, const Point3& p) {
  const double slack = 1e-9 * h;
  if (x >= lo - slack && x <= hi + slack) return;
  throw UserError("", kKey,
                  "point (" + shortest_text(p[0]) + ", " + shortest_text(p[1]) + ", " +
                      shortest_text(p[2]) + ") m is outside the fields' grid (" + axis + " from " +
                      shortest_text(lo) + " to " + shortest_text(hi) + " m)");
}

}  // namespace

std::array<Point3, 2> parse_line_ends(const std::string& text) {
  const auto bad = [&](const std::string& why) -> UserError {
    return UserError("", kKey,
                     "\"" + text + "\": " + why + " (expected \"x0,y0,z0;x1,y1,z1\" in m)");
  };
  const std::size_t semi = text.find(';');
  if (semi == std::string::npos || text.find(';', semi + 1) != std::string::npos)
    throw bad("needs two points separated by one ';'");
  std::array<Point3, 2> ends{};
  for (int e = 0; e < 2; ++e) {
    const std::string part = e == 0 ? text.substr(0, semi) : text.substr(semi + 1);
    std::size_t start = 0;
    for (int a = 0; a < 3; ++a) {
      const std::size_t comma = part.find(',', start);
      if ((a < 2) != (comma != std::string::npos)) throw bad("each point needs three numbers");
      std::string number = part.substr(start, a < 2 ? comma - start : std::string::npos);
      number.erase(0, number.find_first_not_of(" \t"));
      number.erase(number.find_last_not_of(" \t") + 1);
      double v = 0;
      const auto r = std::from_chars(number.data(), number.data() + number.size(), v);
      if (number.empty() || r.ec != std::errc() || r.ptr != number.data() + number.size())
        throw bad("'" + number + "' is not a number");
      if (!std::isfinite(v)) throw bad("'" + number + "' is not finite");
      ends[e][a] = v;
      start = comma + 1;
    }
  }
  return ends;
}

LineSample sample_field(const sim::GridField& f, const Point3& p) {
  const double h = f.spacing_m;
  const bool axi = f.geometry == sim::GridField::Geometry::axisymmetric;
  LineSample out;
  out.position_m = p;
  // The grid coordinates of the point: (r, y, -) axisymmetric, (x, y, z) 3D.
  const double r = std::hypot(p[0], p[2]);
  const Point3 q = axi ? Point3{r, p[1], 0.0} : p;
  for (int a = 0; a < (axi ? 2 : 3); ++a)
    check_inside(q[a], f.origin_m[a], f.origin_m[a] + f.cells[a] * h, h,
                 axi && a == 0 ? 'r' : "xyz"[a], p);
  Bracket b[3];
  for (int a = 0; a < 3; ++a)
    b[a] = axi && a == 2 ? Bracket{} : bracket(q[a], f.origin_m[a], h, f.cells[a]);
  double t = 0, liquid = 0;
  double u[3] = {0, 0, 0};
  for (int corner = 0; corner < 8; ++corner) {
    int idx[3];
    double w = 1;
    for (int a = 0; a < 3; ++a) {
      const bool up = (corner >> a) & 1;
      idx[a] = b[a].lo + (up ? 1 : 0);
      w *= up ? b[a].w : 1 - b[a].w;
    }
    if (w == 0) continue;  // also keeps idx inside a one-cell axis
    const std::size_t c = f.index(idx[0], idx[1], idx[2]);
    t += w * f.temperature_c[c];
    liquid += w * f.water_fraction[c];
    if (f.has_velocity())
      for (int d = 0; d < 3; ++d) u[d] += w * f.velocity_m_s[3 * c + static_cast<std::size_t>(d)];
  }
  out.temperature_c = t;
  out.liquid_fraction = liquid;
  if (!axi) {
    out.velocity_m_s = {u[0], u[1], u[2]};
    return out;
  }
  // Axisymmetric: u_r is odd about the axis, so it falls linearly to 0 inside the first half
  // cell (where the even values are held); then (u_x, u_z) = u_r (x, z) / r.
  double ur = u[0];
  if (r < 0.5 * h) ur *= r / (0.5 * h);
  out.velocity_m_s = {r > 0 ? ur * p[0] / r : 0.0, u[1], r > 0 ? ur * p[2] / r : 0.0};
  return out;
}

std::vector<LineSample> sample_over_line(const sim::GridField& f, const Point3& a, const Point3& b,
                                         long samples) {
  std::vector<LineSample> out;
  out.reserve(static_cast<std::size_t>(samples));
  for (long s = 0; s < samples; ++s) {
    const double t = static_cast<double>(s) / static_cast<double>(samples - 1);
    Point3 p;
    for (int d = 0; d < 3; ++d) p[d] = s + 1 == samples ? b[d] : a[d] + (b[d] - a[d]) * t;
    out.push_back(sample_field(f, p));
  }
  return out;
}

std::string format_line_csv(const std::vector<LineSample>& samples) {
  std::string text = std::string(kLineCsvHeader) + "\n";
  for (const LineSample& s : samples) {
    const double values[] = {s.position_m[0],   s.position_m[1],   s.position_m[2],
                             s.temperature_c,   s.liquid_fraction, s.velocity_m_s[0],
                             s.velocity_m_s[1], s.velocity_m_s[2]};
    // appended piece by piece: GCC 12's -Wrestrict misfires on "," + std::string
    for (std::size_t v = 0; v < std::size(values); ++v) {
      if (v > 0) text.push_back(',');
      text.append(shortest_text(values[v]));
    }
    text.push_back('\n');
  }
  return text;
}

fs::path field_file_of_step(const fs::path& simdir, std::optional<long> step) {
  fs::path dir = simdir / "fields";
  std::error_code ec;
  if (!fs::is_directory(dir, ec) && fs::is_directory(simdir / "sim" / "fields", ec))
    dir = simdir / "sim" / "fields";  // a thaw run folder
  std::vector<fs::path> grids;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".grid") grids.push_back(e.path());
  if (grids.empty())
    throw UserError(simdir.string(), kKey,
                    "no grid fields (fields/step_*.grid): only axisymmetric and 3D runs have them");
  std::sort(grids.begin(), grids.end());  // step_NNNNNN: zero-padded, in step order
  if (!step) return grids.back();
  char name[40];
  std::snprintf(name, sizeof name, "step_%06ld.grid", *step);
  if (*step < 0 || !fs::exists(dir / name))
    throw UserError(simdir.string(), "--step",
                    "no step " + std::to_string(*step) + " in " + dir.string() + " (" +
                        grids.front().stem().string() + " to " + grids.back().stem().string() +
                        ")");
  return dir / name;
}

}  // namespace thaw::inspect
