#include "src/pipeline/handoff_vdb.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <vector>

#include "src/common/atomic_file.h"
#include "src/common/check.h"
#include "src/common/error.h"

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

}  // namespace

std::string vdb_file_name(long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "fields_%06ld.vdb", step);
  return buf;
}

void write_field_vdb(const fs::path& path, const sim::GridField& f,
                     const std::array<double, 3>& offset_m) {
  THAW_CHECK(f.geometry == sim::GridField::Geometry::cartesian3d, "OpenVDB: a 3D field");
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
  const fs::path temp = temporary_sibling(path);
  try {
    openvdb::io::File file(temp.string());
    file.write(grids, meta);
    file.close();
  } catch (const openvdb::Exception& e) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw UserError(path.string(), "", std::string("cannot write OpenVDB file: ") + e.what());
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw UserError(path.string(), "", "cannot rename into place: " + ec.message());
  }
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
    if (f.geometry != sim::GridField::Geometry::cartesian3d) return 0;
    if (written == 0) ensure_directory(out_dir);
    write_field_vdb(out_dir / vdb_file_name(step), f, offset_of(step));
    ++written;
  }
  return written;
}

}  // namespace thaw::pipeline
