#include "src/inspect/field_export.h"

#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "sim/format/grid_field_file.h"

namespace thaw::inspect {
namespace fs = std::filesystem;

void write_vti(const fs::path& path, const sim::GridField& f,
               const std::array<double, 3>& offset_m) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(f.cells[0] + 1, f.cells[1] + 1, f.cells[2] + 1);  // points, not cells
  image->SetOrigin(f.origin_m[0] + offset_m[0], f.origin_m[1] + offset_m[1],
                   f.origin_m[2] + offset_m[2]);
  image->SetSpacing(f.spacing_m, f.spacing_m, f.spacing_m);
  // VTK orders cells x fastest, then y, then z: the solver's index i + nx (j + ny k).
  const auto add = [&](const char* name, const std::vector<float>& values) {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    image->GetCellData()->AddArray(a);
  };
  add("temperature_c", f.temperature_c);
  add("ice_fraction", f.ice_fraction);
  add("water_fraction", f.water_fraction);
  image->GetCellData()->SetActiveScalars("temperature_c");
  if (f.has_velocity()) {
    // (u_x, u_y, u_z) per cell, as the field holds it: ParaView's Glyph and Stream Tracer take it.
    vtkNew<vtkFloatArray> a;
    a->SetName("velocity_m_s");
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(static_cast<vtkIdType>(f.cell_count()));
    std::copy(f.velocity_m_s.begin(), f.velocity_m_s.end(), a->GetPointer(0));
    image->GetCellData()->AddArray(a);
    image->GetCellData()->SetActiveVectors("velocity_m_s");
  }
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  // Each array inline (base64 in its DataArray element), no appended section: VTK reads an
  // appended section (raw or base64) by stopping its expat parser at <AppendedData>, which
  // expat's reparse deferral (expat 2.6, backported into Debian 12's security updates:
  // 2.5.0-1+deb12u5) defeats. Debian 12's ParaView 5.11 then fails on such files with "not
  // well-formed (invalid token)" (VTK issue 19258; seen with data/paraview/check_in_debian.sh).
  // Written to memory, then to the file atomically: VTK 9.1's inline mode crashes when the disk
  // fills mid-file (it frees position arrays only appended mode allocates).
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  writer->WriteToOutputStringOn();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw UserError(path.string(), "", "cannot write VTK ImageData");
  write_file_atomic(path, writer->GetOutputString());
}

long write_field_series(const fs::path& simdir, const fs::path& out_pvd,
                        const ProgressCallback& progress, const StepPlacement& placement) {
  std::vector<fs::path> grids;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(simdir / "fields", ec))
    if (e.path().extension() == ".grid") grids.push_back(e.path());
  if (grids.empty()) return 0;
  std::sort(grids.begin(), grids.end());  // step_NNNNNN: zero-padded, so in step order
  const fs::path data_dir = out_pvd.parent_path() / (out_pvd.stem().string() + "_vti");
  ensure_directory(data_dir);
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<!-- thaw: the grid solver's fields (cell data temperature_c, ice_fraction, "
      "water_fraction); timestep = simulated time [s]. -->\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  long done = 0;
  for (const fs::path& grid : grids) {
    const sim::GridField field = sim::read_grid_field(grid);
    const std::string name = grid.stem().string() + ".vti";
    // step_NNNNNN.grid: the step the placement is for.
    const long step = std::strtol(grid.stem().string().c_str() + 5, nullptr, 10);
    write_vti(data_dir / name, field, placement ? placement(step) : std::array<double, 3>{0, 0, 0});
    char time[40];
    std::snprintf(time, sizeof time, "%.17g", field.time_s);
    xml += "    <DataSet timestep=\"" + std::string(time) + "\" part=\"0\" file=\"" +
           data_dir.filename().string() + "/" + name + "\"/>\n";
    if (progress) progress(++done, static_cast<std::int64_t>(grids.size()));
  }
  xml += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(out_pvd, xml);
  return static_cast<long>(grids.size());
}

}  // namespace thaw::inspect
