#include "src/pipeline/handoff_vdb.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "base/fnv_hash.h"
#include "sim/format/grid_field_file.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

/// The grid `name` of `values` (one per cell), voxels whose value differs from `background` set
/// (all of them when `dense`), with the cell-centre transform of handoff_vdb.h.
openvdb::FloatGrid::Ptr float_grid(const sim::GridField& f, const std::vector<float>& values,
                                   const std::string& name, bool dense,
                                   const openvdb::math::Transform::Ptr& transform) {
  const float background = 0.0f;
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
  grid->setName(name);
  grid->setTransform(transform);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto access = grid->getAccessor();
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i) {
        const float v = values[f.index(i, j, k)];
        if (dense || v != background) access.setValue(openvdb::Coord(i, j, k), v);
      }
  return grid;
}

/// Where OpenVDB's archive header (io/Archive.cc, writeHeader; file format 224 of OpenVDB 10)
/// holds the stream's identifier: after the magic number (int64), the file format version and the
/// library's major and minor version (uint32 each) and the has-grid-offsets flag (char), as 36
/// characters of text, 8-4-4-4-12 hex digits.
constexpr std::size_t kUuidOffset = 8 + 4 + 4 + 4 + 1;
constexpr std::size_t kUuidLength = 36;
constexpr std::int64_t kVdbMagic = 0x56444220;

bool is_uuid_text(std::string_view t) {
  if (t.size() != kUuidLength) return false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? t[i] != '-' : !std::isxdigit(static_cast<unsigned char>(t[i]))) return false;
  }
  return true;
}

/// Replaces the random identifier OpenVDB writes into every file (a new one per write, so two runs
/// and any resume differed) by one derived from the rest of the file's bytes: the same content
/// gives the same identifier, different content a different one, as OpenVDB's
/// Archive::isIdentical expects. 128 bits of two FNV-1a hashes from different starting states,
/// marked as an RFC 9562 version 8 (custom) UUID.
void make_uuid_reproducible(std::string& bytes) {
  std::int64_t magic = 0;
  THAW_CHECK(bytes.size() > kUuidOffset + kUuidLength, "an OpenVDB file shorter than its header");
  std::memcpy(&magic, bytes.data(), sizeof magic);
  THAW_CHECK(magic == kVdbMagic, "not an OpenVDB file header");
  THAW_CHECK(is_uuid_text(std::string_view(bytes).substr(kUuidOffset, kUuidLength)),
             "OpenVDB's header holds no 36-character UUID where format 224 puts it");
  std::string rest = bytes;
  rest.replace(kUuidOffset, kUuidLength, kUuidLength, '0');
  const std::uint64_t hi = fnv1a_64(rest), lo = fnv1a_64(rest, fnv1a_64("thaw vdb uuid"));
  unsigned char b[16];
  for (int i = 0; i < 8; ++i) {
    b[i] = static_cast<unsigned char>(hi >> (56 - 8 * i));
    b[8 + i] = static_cast<unsigned char>(lo >> (56 - 8 * i));
  }
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x80);  // version 8
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);  // variant 10
  char text[kUuidLength + 1];
  std::snprintf(text, sizeof text,
                "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x", b[0], b[1],
                b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14],
                b[15]);
  bytes.replace(kUuidOffset, kUuidLength, text, kUuidLength);
}

}  // namespace

sim::GridField revolved_field(const sim::GridField& a) {
  if (a.geometry != sim::GridField::Geometry::axisymmetric) return a;
  THAW_CHECK(a.cells[2] == 1, "an axisymmetric field is one cell deep");
  const int nr = a.cells[0], ny = a.cells[1];
  const double h = a.spacing_m;
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  f.cells = {2 * nr, ny, 2 * nr};
  f.origin_m = {-nr * h, a.origin_m[1], -nr * h};
  f.spacing_m = h;
  f.time_s = a.time_s;
  const std::size_t n = f.cell_count();
  f.temperature_c.resize(n), f.ice_fraction.resize(n), f.water_fraction.resize(n);
  for (int k = 0; k < 2 * nr; ++k)
    for (int i = 0; i < 2 * nr; ++i) {
      // The centre's distance from the axis, in cells: hypot of (i + 1/2 - nr, k + 1/2 - nr).
      const double r = std::hypot(i + 0.5 - nr, k + 0.5 - nr);
      const int ring = std::min(nr - 1, static_cast<int>(r));
      for (int j = 0; j < ny; ++j) {
        const std::size_t to = f.index(i, j, k), from = a.index(ring, j, 0);
        f.temperature_c[to] = a.temperature_c[from];
        f.ice_fraction[to] = a.ice_fraction[from];
        f.water_fraction[to] = a.water_fraction[from];
      }
    }
  return f;
}

std::string vdb_file_name(long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "fields_%06ld.vdb", step);
  return buf;
}

void write_field_vdb(const fs::path& path, const sim::GridField& field,
                     const std::array<double, 3>& offset_m) {
  const sim::GridField f = revolved_field(field);
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
  const double h = f.spacing_m;
  // Index space to world: scale by the cell edge, then move index (0,0,0) to cell (0,0,0)'s
  // centre in the world.
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(h);
  transform->postTranslate(openvdb::Vec3d(f.origin_m[0] + 0.5 * h + offset_m[0],
                                          f.origin_m[1] + 0.5 * h + offset_m[1],
                                          f.origin_m[2] + 0.5 * h + offset_m[2]));
  openvdb::GridPtrVec grids{float_grid(f, f.temperature_c, "temperature_c", true, transform),
                            float_grid(f, f.ice_fraction, "ice_fraction", false, transform),
                            float_grid(f, f.water_fraction, "water_fraction", false, transform)};
  openvdb::MetaMap meta;
  meta.insertMeta("time_s", openvdb::DoubleMetadata(f.time_s));
  meta.insertMeta("creator", openvdb::StringMetadata("thaw run (inspect stage)"));
  // OpenVDB writes to a file name only (with the grid offsets a reader seeks by); the bytes are
  // then read back, given a reproducible identifier and written atomically under the final name.
  const fs::path temp = temporary_sibling(path);
  std::string bytes;
  try {
    openvdb::io::File file(temp.string());
    file.write(grids, meta);
    file.close();
    std::ifstream in(temp, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw UserError(path.string(), "", "cannot read back the OpenVDB file");
  } catch (const openvdb::Exception& e) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw UserError(path.string(), "", std::string("cannot write OpenVDB file: ") + e.what());
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw;
  }
  std::error_code ec;
  fs::remove(temp, ec);
  make_uuid_reproducible(bytes);
  write_file_atomic(path, bytes);
}

long write_vdb_sequence(const fs::path& simdir, const fs::path& out_dir,
                        const std::function<std::array<double, 3>(long step)>& offset_of) {
  std::vector<std::pair<long, fs::path>> grids;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(simdir / "fields", ec)) {
    const std::string name = e.path().filename().string();
    long step = 0;
    if (e.path().extension() == ".grid" && std::sscanf(name.c_str(), "step_%ld.grid", &step) == 1)
      grids.emplace_back(step, e.path());
  }
  std::sort(grids.begin(), grids.end());
  long written = 0;
  for (const auto& [step, file] : grids) {
    const sim::GridField f = sim::read_grid_field(file);
    if (written == 0) ensure_directory(out_dir);
    write_field_vdb(out_dir / vdb_file_name(step), f, offset_of(step));
    ++written;
  }
  return written;
}

}  // namespace thaw::pipeline
