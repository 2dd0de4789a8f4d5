// The grid runs' field files (sim/format/grid_field_file.h): a field survives write + read bit for
// bit, and every kind of damage is refused with a UserError naming the file.
#include "sim/format/grid_field_file.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "base/error.h"
#include "base/fnv_hash.h"

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(THAW_BINARY_DIR) / "test-tmp" / "grid_field" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

GridField sample_field(GridField::Geometry geometry) {
  GridField f;
  f.geometry = geometry;
  f.cells = geometry == GridField::Geometry::axisymmetric ? std::array<int, 3>{5, 7, 1}
                                                          : std::array<int, 3>{3, 4, 5};
  // an axisymmetric field starts on the axis (x = z = 0)
  f.origin_m = geometry == GridField::Geometry::axisymmetric
                   ? std::array<double, 3>{0.0, -0.02, 0.0}
                   : std::array<double, 3>{-0.0125, -0.02, 0.003};
  f.spacing_m = 0.0025;
  f.time_s = 123.456789012345;
  const std::size_t n = f.cell_count();
  for (std::size_t i = 0; i < n; ++i) {
    // distinct, non-trivial values in every cell so that a transposed or shifted array shows
    const double x = static_cast<double>(i) / static_cast<double>(n);
    f.temperature_c.push_back(
        static_cast<float>(-12.5 + 40.0 * x * x + 1e-3 * static_cast<double>(i % 3)));
    f.ice_fraction.push_back(static_cast<float>(0.7 * x));
    f.water_fraction.push_back(static_cast<float>(0.3 * (1 - x)));
  }
  return f;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// read_grid_field must refuse `bytes` with a one-line UserError that names the file.
void expect_refused(const fs::path& file, const std::string& bytes, const std::string& fragment) {
  write_bytes(file, bytes);
  try {
    read_grid_field(file);
    FAIL() << "accepted a damaged file (" << fragment << ")";
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(GridField, RoundTripIsBitExactForBothGeometries) {
  const fs::path dir = fresh_dir("round_trip");
  for (auto geometry : {GridField::Geometry::axisymmetric, GridField::Geometry::cartesian3d}) {
    const GridField f = sample_field(geometry);
    const fs::path file = dir / (std::string(to_string(geometry)) + ".grid");
    write_grid_field(file, f);
    const GridField g = read_grid_field(file);
    EXPECT_EQ(g.geometry, f.geometry);
    EXPECT_EQ(g.cells, f.cells);
    EXPECT_EQ(g.origin_m, f.origin_m);
    EXPECT_EQ(g.spacing_m, f.spacing_m);
    EXPECT_EQ(g.time_s, f.time_s);
    EXPECT_EQ(g.temperature_c, f.temperature_c);
    EXPECT_EQ(g.ice_fraction, f.ice_fraction);
    EXPECT_EQ(g.water_fraction, f.water_fraction);
  }
  // atomic write: nothing but the two files is left in the folder
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

// The version-1 layout, byte for byte: 80 bytes of header and payload, then the checksum. The
// expected checksum was computed outside thaw (FNV-1a with the format's starting state
// 1469598103934665603, a digit short of FNV's offset basis, over these 80 bytes), so a change of
// the hash or of its starting state, which would make every existing file unreadable, fails here.
TEST(GridField, WritesTheVersion1LayoutAndChecksum) {
  GridField f;
  f.geometry = GridField::Geometry::cartesian3d;
  f.cells = {1, 1, 1};
  f.origin_m = {0.0, 0.0, 0.0};
  f.spacing_m = 0.01;
  f.time_s = 1.5;
  f.temperature_c = {-1.0f};
  f.ice_fraction = {0.25f};
  f.water_fraction = {0.75f};
  const fs::path file = fresh_dir("layout") / "one_cell.grid";
  write_grid_field(file, f);
  const std::string bytes = read_bytes(file);
  ASSERT_EQ(bytes.size(), 88u);
  EXPECT_EQ(bytes.substr(0, 8), "THAWGRID");
  std::uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + 80, sizeof checksum);
  EXPECT_EQ(checksum, 0x029d73794a79ca9bULL);
  EXPECT_EQ(read_grid_field(file).temperature_c, f.temperature_c);
}

TEST(GridField, IndexRunsFastestAlongTheFirstAxis) {
  const GridField f = sample_field(GridField::Geometry::cartesian3d);
  EXPECT_EQ(f.index(1, 0, 0), 1u);
  EXPECT_EQ(f.index(0, 1, 0), 3u);
  EXPECT_EQ(f.index(0, 0, 1), 12u);
  EXPECT_EQ(f.index(2, 3, 4), f.cell_count() - 1);
}

TEST(GridField, DamagedFilesAreRefusedNamingTheFile) {
  const fs::path dir = fresh_dir("damaged");
  const fs::path good = dir / "good.grid";
  write_grid_field(good, sample_field(GridField::Geometry::cartesian3d));
  const std::string bytes = read_bytes(good);
  const fs::path bad = dir / "bad.grid";

  expect_refused(bad, "", "truncated");
  expect_refused(bad, bytes.substr(0, bytes.size() / 2), "truncated");
  expect_refused(bad, bytes.substr(0, bytes.size() - 1), "truncated");
  expect_refused(bad, bytes + "x", "unexpected bytes");
  std::string magic = bytes;
  magic[0] = 'X';
  expect_refused(bad, magic, "bad magic");
  std::string version = bytes;
  version[8] = 9;
  expect_refused(bad, version, "version 9");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;  // one bit inside the temperatures
  expect_refused(bad, flipped, "checksum");
  std::string cells = bytes;
  cells[16] = 0;  // nx = 0 (little-endian int32 after magic, version, geometry)
  cells[17] = cells[18] = cells[19] = 0;
  expect_refused(bad, cells, "not positive");
  try {
    read_grid_field(dir / "missing.grid");
    FAIL() << "read a missing file";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.grid"), std::string::npos);
  }
}

/// `bytes` (a version-1 file) with the double at `offset` set to `v` and the checksum recomputed
/// (FNV-1a from the format's starting state, grid_field_file.cpp): a header that is absurd but
/// not damaged.
std::string with_header_double(std::string bytes, std::size_t offset, double v) {
  std::memcpy(bytes.data() + offset, &v, sizeof v);
  const std::uint64_t sum =
      fnv1a_64(std::string_view(bytes).substr(0, bytes.size() - 8), 1469598103934665603ULL);
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, sizeof sum);
  return bytes;
}

// The bad-input campaign of issue 27: spacings of 1e308 ... 5e-324 m and origins of +-1e308 m
// with valid checksums made `thaw mesh` die by SIGSEGV / SIGFPE or allocate until the OOM killer.
// Offsets: magic 8, version 4, geometry 4, cells 3 x 4 -> origin at 28, spacing at 52.
TEST(GridField, AbsurdButFiniteSpacingOrOriginIsRefusedNamingTheHeaderField) {
  const fs::path dir = fresh_dir("absurd_header");
  for (auto geometry : {GridField::Geometry::axisymmetric, GridField::Geometry::cartesian3d}) {
    const fs::path good = dir / "good.grid";
    write_grid_field(good, sample_field(geometry));
    const std::string bytes = read_bytes(good);
    const fs::path bad = dir / "bad.grid";
    for (double h : {1e308, 1e300, 1e100, 101.0, 9.99e-10, 1e-20, 5e-324, 0.0, -1.0}) {
      SCOPED_TRACE(h);
      write_bytes(bad, with_header_double(bytes, 52, h));
      try {
        read_grid_field(bad);
        FAIL() << "accepted a spacing of " << h;
      } catch (const UserError& e) {
        EXPECT_EQ(e.file(), bad.string());
        EXPECT_EQ(e.where(), "spacing_m");
      }
    }
    for (double o : {1e308, -1e308, 1e4, -1001.0}) {
      SCOPED_TRACE(o);
      write_bytes(bad, with_header_double(bytes, 36, o));  // origin y (the axis of both kinds)
      try {
        read_grid_field(bad);
        FAIL() << "accepted an origin of " << o;
      } catch (const UserError& e) {
        EXPECT_EQ(e.where(), "origin_m");
        EXPECT_NE(e.problem().find("axis y"), std::string::npos) << e.what();
      }
    }
    if (geometry == GridField::Geometry::axisymmetric) {
      write_bytes(bad, with_header_double(bytes, 28, -1e308));  // origin x: the axis is at 0
      EXPECT_THROW(read_grid_field(bad), UserError);
    }
    // The bounds themselves are fields thaw can write: a 1 nm and a 100 m cell, a grid ending
    // (1 um short of) 1 km from the origin.
    for (double h : {kMinFieldSpacingM, kMaxFieldSpacingM}) {
      write_bytes(bad, with_header_double(bytes, 52, h));
      EXPECT_EQ(read_grid_field(bad).spacing_m, h);
    }
    const GridField f = sample_field(geometry);
    const double top = kMaxFieldCoordinateM - f.cells[1] * f.spacing_m - 1e-6;
    write_bytes(bad, with_header_double(bytes, 36, top));
    EXPECT_EQ(read_grid_field(bad).origin_m[1], top);
  }
}

/// sample_field with a velocity: distinct components in every cell (axisymmetric: u_z = 0).
GridField moving_field(GridField::Geometry geometry) {
  GridField f = sample_field(geometry);
  const std::size_t n = f.cell_count();
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n);
    f.velocity_m_s.push_back(static_cast<float>(1e-3 * (x - 0.5)));
    f.velocity_m_s.push_back(static_cast<float>(-2e-3 * x * x));
    f.velocity_m_s.push_back(
        geometry == GridField::Geometry::axisymmetric ? 0.0f : static_cast<float>(3e-4 * x));
  }
  return f;
}

TEST(GridField, VelocityRoundTripsBitExactAsVersion2) {
  const fs::path dir = fresh_dir("velocity");
  for (auto geometry : {GridField::Geometry::axisymmetric, GridField::Geometry::cartesian3d}) {
    const GridField f = moving_field(geometry);
    const fs::path file = dir / (std::string(to_string(geometry)) + ".grid");
    write_grid_field(file, f);
    const std::string bytes = read_bytes(file);
    std::uint32_t version = 0;
    std::memcpy(&version, bytes.data() + 8, sizeof version);
    EXPECT_EQ(version, 2u);
    // 68 bytes of header, 12 n of temperatures and fractions, 12 n of velocity, the checksum
    EXPECT_EQ(bytes.size(), 68 + 24 * f.cell_count() + 8);
    const GridField g = read_grid_field(file);
    EXPECT_TRUE(g.has_velocity());
    EXPECT_EQ(g.velocity_m_s, f.velocity_m_s);
    EXPECT_EQ(g.temperature_c, f.temperature_c);
    EXPECT_EQ(g.water_fraction, f.water_fraction);
  }
}

// A field without velocity is written as before the velocity was kept (version 1), so runs
// without flow stay byte-identical, and files written then still read (no velocity).
TEST(GridField, WithoutVelocityTheFileIsVersion1AndReadsWithoutVelocity) {
  const fs::path dir = fresh_dir("still");
  const GridField moving = moving_field(GridField::Geometry::cartesian3d);
  GridField still = moving;
  still.velocity_m_s.clear();
  write_grid_field(dir / "still.grid", still);
  write_grid_field(dir / "moving.grid", moving);
  const std::string a = read_bytes(dir / "still.grid"), b = read_bytes(dir / "moving.grid");
  std::uint32_t version = 0;
  std::memcpy(&version, a.data() + 8, sizeof version);
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(a.size(), 68 + 12 * still.cell_count() + 8);
  // the same bytes up to the velocity but for the version
  EXPECT_EQ(a.substr(12, a.size() - 20), b.substr(12, a.size() - 20));
  EXPECT_FALSE(read_grid_field(dir / "still.grid").has_velocity());
}

TEST(GridField, DamagedVelocitiesAreRefused) {
  const fs::path dir = fresh_dir("bad_velocity");
  const fs::path good = dir / "good.grid";
  const GridField f = moving_field(GridField::Geometry::cartesian3d);
  write_grid_field(good, f);
  const std::string bytes = read_bytes(good);
  const fs::path bad = dir / "bad.grid";
  // cut inside the velocities: truncated, naming them
  expect_refused(bad, bytes.substr(0, bytes.size() - 8 - 6), "velocities");
  // a version-2 header over a version-1 body: the velocities are missing
  GridField still = f;
  still.velocity_m_s.clear();
  write_grid_field(good, still);
  std::string relabelled = read_bytes(good);
  relabelled[8] = 2;
  expect_refused(bad, relabelled, "truncated");
  // an absurd or non-finite component with a valid checksum
  for (float v : {2e3f, -1e30f, std::numeric_limits<float>::infinity(),
                  std::numeric_limits<float>::quiet_NaN()}) {
    GridField g = f;
    g.velocity_m_s[3 * 5 + 1] = v;
    write_grid_field(good, g);
    expect_refused(bad, read_bytes(good), "velocity component 1 of cell 5");
  }
}

TEST(GridField, OutOfRangeFractionsAreRefused) {
  const fs::path dir = fresh_dir("fractions");
  GridField f = sample_field(GridField::Geometry::axisymmetric);
  f.ice_fraction[3] = 0.8f;
  f.water_fraction[3] = 0.5f;  // 1.3 of the cell's volume
  write_grid_field(dir / "f.grid", f);
  EXPECT_THROW(read_grid_field(dir / "f.grid"), UserError);
}

}  // namespace
}  // namespace thaw::sim
