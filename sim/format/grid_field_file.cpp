#include "sim/format/grid_field_file.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "base/fnv_hash.h"

namespace thaw::sim {

static_assert(std::endian::native == std::endian::little, "the .grid format is little-endian");

namespace {

constexpr char kMagic[8] = {'T', 'H', 'A', 'W', 'G', 'R', 'I', 'D'};
/// Version 1: temperatures and fractions; version 2: the same, then the velocity (3 floats per
/// cell). The writer picks the lowest version that holds the field.
constexpr std::uint32_t kVersionWithoutVelocity = 1;
constexpr std::uint32_t kVersionWithVelocity = 2;
/// Larger grids are refused as corrupt (2^31 cells would be 24 GiB of fields).
constexpr std::uint64_t kMaxCells = std::uint64_t{1} << 31;
/// float rounding of fractions that sum to 1 in double precision.
constexpr float kFractionSlack = 1e-5f;

/// The checksum: FNV-1a over the payload (base/fnv_hash.h), cheap and enough to catch
/// damaged or spliced files. Its starting state is not FNV's offset basis (kFnv1aOffset,
/// 14695981039346656037) but this number a digit short of it, which the first writer used: every
/// version-1 file carries checksums from it, so it stays part of the format (changing it would
/// need a version 2 and would make existing files unreadable for no gain).
constexpr std::uint64_t kChecksumStart = 1469598103934665603ULL;

std::uint64_t checksum(std::string_view payload) {
  return fnv1a_64(payload, kChecksumStart);
}

template <class T>
void put(std::string& out, const T& v) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// Sequential reader over the file's bytes; every overrun is a truncated file.
class Reader {
 public:
  Reader(const std::string& bytes, const std::string& name) : m_bytes(bytes), m_name(name) {}
  template <class T>
  T get(const char* what) {
    T v;
    need(sizeof(T), what);
    std::memcpy(&v, m_bytes.data() + m_pos, sizeof(T));
    m_pos += sizeof(T);
    return v;
  }
  void floats(std::vector<float>& out, std::size_t n, const char* what) {
    need(n * sizeof(float), what);
    out.resize(n);
    std::memcpy(out.data(), m_bytes.data() + m_pos, n * sizeof(float));
    m_pos += n * sizeof(float);
  }
  std::size_t position() const { return m_pos; }
  std::size_t size() const { return m_bytes.size(); }

 private:
  void need(std::size_t n, const char* what) const {
    if (m_bytes.size() - m_pos < n)
      throw UserError(m_name, "",
                      std::string("truncated grid field file (ends inside the ") + what + ")");
  }
  const std::string& m_bytes;
  const std::string& m_name;
  std::size_t m_pos = 0;
};

}  // namespace

void write_grid_field(const std::filesystem::path& file, const GridField& f) {
  const std::size_t n = f.cell_count();
  THAW_CHECK(f.cells[0] > 0 && f.cells[1] > 0 && f.cells[2] > 0, "grid field with an empty axis");
  THAW_CHECK(f.geometry != GridField::Geometry::axisymmetric || f.cells[2] == 1,
             "axisymmetric fields have nz = 1");
  THAW_CHECK(
      f.temperature_c.size() == n && f.ice_fraction.size() == n && f.water_fraction.size() == n,
      "grid field arrays must have one value per cell");
  THAW_CHECK(!f.has_velocity() || f.velocity_m_s.size() == 3 * n,
             "a grid field's velocity has three values per cell");
  std::string out;
  out.reserve(96 + (f.has_velocity() ? 6 : 3) * n * sizeof(float));
  out.append(kMagic, sizeof kMagic);
  put(out, f.has_velocity() ? kVersionWithVelocity : kVersionWithoutVelocity);
  put(out, static_cast<std::uint32_t>(f.geometry == GridField::Geometry::axisymmetric ? 0 : 1));
  for (int c : f.cells) put(out, static_cast<std::int32_t>(c));
  for (double o : f.origin_m) put(out, o);
  put(out, f.spacing_m);
  put(out, f.time_s);
  for (const auto* a : {&f.temperature_c, &f.ice_fraction, &f.water_fraction, &f.velocity_m_s})
    out.append(reinterpret_cast<const char*>(a->data()), a->size() * sizeof(float));
  put(out, checksum(out));
  write_file_atomic(file, out);
}

GridField read_grid_field(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw UserError(name, "", std::filesystem::exists(file) ? "cannot be read" : "file not found");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw UserError(name, "", "read error");
  auto fail = [&](const std::string& problem) { throw UserError(name, "", problem); };

  Reader r(bytes, name);
  char magic[sizeof kMagic];
  for (char& c : magic) c = r.get<char>("header");
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    fail("not a thaw grid field file (bad magic)");
  const auto version = r.get<std::uint32_t>("header");
  if (version != kVersionWithoutVelocity && version != kVersionWithVelocity)
    fail("grid field format version " + std::to_string(version) + " is not supported (expected " +
         std::to_string(kVersionWithoutVelocity) + " or " + std::to_string(kVersionWithVelocity) +
         ")");
  GridField f;
  const auto geometry = r.get<std::uint32_t>("header");
  if (geometry > 1) fail("unknown geometry code " + std::to_string(geometry));
  f.geometry = geometry == 0 ? GridField::Geometry::axisymmetric : GridField::Geometry::cartesian3d;
  std::uint64_t n = 1;
  for (int& c : f.cells) {
    c = r.get<std::int32_t>("header");
    if (c <= 0) fail("cell count " + std::to_string(c) + " is not positive");
    n *= static_cast<std::uint64_t>(c);
    if (n > kMaxCells) fail("implausible grid size (more than 2^31 cells)");
  }
  if (f.geometry == GridField::Geometry::axisymmetric && f.cells[2] != 1)
    fail("an axisymmetric field must have cells[2] = 1, got " + std::to_string(f.cells[2]));
  for (double& o : f.origin_m) o = r.get<double>("header");
  f.spacing_m = r.get<double>("header");
  f.time_s = r.get<double>("header");
  // Before any cell is read: a header the mesher cannot place in space (a spacing of 1e300 m,
  // an origin of 1e308 m) is refused here, naming the header field, however valid the checksum.
  if (const auto p = find_header_problem(f)) throw UserError(name, p->field, p->problem);
  r.floats(f.temperature_c, n, "temperatures");
  r.floats(f.ice_fraction, n, "ice fractions");
  r.floats(f.water_fraction, n, "water fractions");
  if (version == kVersionWithVelocity) r.floats(f.velocity_m_s, 3 * n, "velocities");
  const std::size_t payload = r.position();
  const auto stored_checksum = r.get<std::uint64_t>("checksum");
  if (r.position() != r.size()) fail("unexpected bytes after the checksum");
  if (stored_checksum != checksum(std::string_view(bytes).substr(0, payload)))
    fail("checksum mismatch (the file is damaged)");
  for (std::size_t i = 0; i < n; ++i) {
    const float t = f.temperature_c[i], ice = f.ice_fraction[i], water = f.water_fraction[i];
    if (!std::isfinite(t) || !std::isfinite(ice) || !std::isfinite(water))
      fail("non-finite value in cell " + std::to_string(i));
    if (ice < 0 || ice > 1 || water < 0 || water > 1 || ice + water > 1 + kFractionSlack)
      fail("volume fractions out of [0, 1] in cell " + std::to_string(i));
  }
  for (std::size_t i = 0; i < f.velocity_m_s.size(); ++i)
    if (!(std::abs(f.velocity_m_s[i]) <= kMaxFieldSpeedM_S))
      fail("velocity component " + std::to_string(i % 3) + " of cell " + std::to_string(i / 3) +
           " is not finite or faster than " + std::to_string(static_cast<int>(kMaxFieldSpeedM_S)) +
           " m/s");
  return f;
}

}  // namespace thaw::sim
