#include "src/inspect/pvd_writer.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cstdio>

#include "src/common/atomic_file.h"
#include "src/common/error.h"
#include "src/inspect/simulation_folder.h"
#include "src/inspect/vtk_messages.h"
#include "src/inspect/vtk_polydata.h"
#include "src/meshio/obj_reader.h"

namespace thaw::inspect {
namespace fs = std::filesystem;
namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* part_name(int part) { return part == 0 ? "inner" : "outer"; }

}  // namespace

void write_vtp(const fs::path& path, const TriangleMesh& mesh) {
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh);
  const fs::path temp = temporary_sibling(path);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetFileName(temp.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  const VtkMessages messages;  // VTK's own error lines go into the UserError, not to stderr
  const int ok = writer->Write();
  std::error_code ec;
  if (ok != 1 || writer->GetErrorCode() != 0) {
    fs::remove(temp, ec);
    throw UserError(path.string(), "",
                    "cannot write VTK PolyData (disk full or not writable)" + messages.suffix());
  }
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw UserError(path.string(), "", "cannot rename into place: " + ec.message());
  }
}

PvdWriter::PvdWriter(fs::path pvd_path) : m_pvd(std::move(pvd_path)) {
  if (m_pvd.filename().empty()) throw UserError(m_pvd.string(), "", "not a file name");
  m_data_dir = m_pvd.parent_path() / (m_pvd.stem().string() + "_vtp");
  ensure_directory(m_pvd.parent_path());
  ensure_directory(m_data_dir);
}

void PvdWriter::add(long step, double time_s, SurfacePart part, const TriangleMesh* mesh) {
  const int p = static_cast<int>(part);
  char name[64];
  std::snprintf(name, sizeof name, "step_%06ld_%s.vtp", step, part_name(p));
  write_vtp(m_data_dir / name, mesh ? *mesh : TriangleMesh{});
  const std::string rel = m_data_dir.filename().string() + "/" + name;
  // Replace an earlier entry for the same time and part (a re-meshed step), else append.
  auto same = [&](const Entry& e) { return e.part == p && e.file == rel; };
  auto it = std::find_if(m_entries.begin(), m_entries.end(), same);
  if (it != m_entries.end()) it->time_s = time_s;
  else m_entries.push_back({time_s, p, rel});
  std::stable_sort(m_entries.begin(), m_entries.end(), [](const Entry& a, const Entry& b) {
    return a.time_s != b.time_s ? a.time_s < b.time_s : a.part < b.part;
  });
}

void PvdWriter::commit() const {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<!-- thaw: inner (part 0) = water|ice front, outer (part 1) = ice|air surface;\n"
      "     timestep = simulated time [s]. -->\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char buf[96];
  for (const Entry& e : m_entries) {
    std::snprintf(buf, sizeof buf, "%.17g", e.time_s);
    xml += "    <DataSet timestep=\"" + std::string(buf) + "\" group=\"\" part=\"" +
           std::to_string(e.part) + "\" name=\"" + part_name(e.part) + "\" file=\"" +
           xml_escape(e.file) + "\"/>\n";
  }
  xml += "  </Collection>\n</VTKFile>\n";
  write_file_atomic(m_pvd, xml);
}

void write_pvd_series(const fs::path& simdir, const fs::path& out_pvd,
                      const ProgressCallback& progress) {
  const SimulationFolder folder = read_simulation_folder(simdir);
  if (!folder.meshed)
    throw UserError((simdir / "mesh" / "manifest.json").string(), "",
                    "not found: mesh the simulation first (thaw mesh)");
  PvdWriter writer(out_pvd);
  const auto total = static_cast<std::int64_t>(folder.steps.size());
  std::int64_t done = 0;
  for (const MeshedStep& s : folder.steps) {
    for (const SurfacePart part : {SurfacePart::inner, SurfacePart::outer}) {
      const auto& file = part == SurfacePart::inner ? s.inner : s.outer;
      if (file) {
        const TriangleMesh mesh = meshio::read_obj(*file);
        writer.add(s.step, s.time_s, part, &mesh);
      } else {
        writer.add(s.step, s.time_s, part, nullptr);
      }
    }
    if (progress) progress(++done, total);
  }
  writer.commit();
}

}  // namespace thaw::inspect
