#include "src/inspect/field_export.h"

#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "src/common/atomic_file.h"
#include "src/common/error.h"

namespace thaw::inspect {
namespace fs = std::filesystem;

void write_vti(const fs::path& path, const sim::GridField& f) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(f.cells[0] + 1, f.cells[1] + 1, f.cells[2] + 1);  // points, not cells
  image->SetOrigin(f.origin_m.data());
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
  const fs::path temp = temporary_sibling(path);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(temp.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  std::error_code ec;
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    fs::remove(temp, ec);
    throw UserError(path.string(), "", "cannot write VTK ImageData (disk full or not writable)");
  }
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw UserError(path.string(), "", "cannot rename into place: " + ec.message());
  }
}

long write_field_series(const fs::path& simdir, const fs::path& out_pvd,
                        const ProgressCallback& progress) {
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
    write_vti(data_dir / name, field);
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
