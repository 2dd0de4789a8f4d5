#include "src/inspect/pvd_writer.h"

#include <vtkDataCompressor.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/obj_reader.h"
#include "base/outcome.h"
#include "sim/format/grid_field_file.h"
#include "src/inspect/field_probe.h"
#include "src/inspect/simulation_folder.h"
#include "src/inspect/vtk_messages.h"
#include "src/inspect/vtk_polydata.h"

namespace thaw::inspect {
namespace fs = std::filesystem;
namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

const char* part_name(int part) {
  return part == 0 ? "inner" : "outer";
}

}  // namespace

std::vector<std::array<double, 3>> vertex_normals(const TriangleMesh& mesh) {
  std::vector<std::array<double, 3>> n(mesh.vertices.size(), {0.0, 0.0, 0.0});
  const bool own = !mesh.normal_triangles.empty();
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    if (own) {
      for (int c = 0; c < 3; ++c) {
        const auto& fn = mesh.normals[static_cast<std::size_t>(mesh.normal_triangles[f][c])];
        auto& vn = n[static_cast<std::size_t>(t[c])];
        for (int k = 0; k < 3; ++k) vn[k] += fn[k];
      }
      continue;
    }
    const auto& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const auto& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const auto& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) n[static_cast<std::size_t>(t[corner])][k] += cross[k];
  }
  for (auto& v : n) {
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0)
      for (double& x : v) x /= len;
  }
  return n;
}

void write_vtp(const fs::path& path, const TriangleMesh& mesh,
               const std::vector<PointScalars>& scalars) {
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh);
  for (const PointScalars& s : scalars) {
    THAW_CHECK(s.values.size() == mesh.vertices.size(), "one point data value per vertex");
    vtkNew<vtkDoubleArray> array;
    array->SetName(s.name.c_str());
    array->SetNumberOfTuples(static_cast<vtkIdType>(s.values.size()));
    for (std::size_t i = 0; i < s.values.size(); ++i)
      array->SetValue(static_cast<vtkIdType>(i), s.values[i]);
    if (&s == &scalars.front())
      poly->GetPointData()->SetScalars(array);
    else
      poly->GetPointData()->AddArray(array);
  }
  if (!mesh.triangles.empty()) {
    const auto normals = vertex_normals(mesh);
    vtkNew<vtkDoubleArray> array;
    array->SetName("Normals");
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(static_cast<vtkIdType>(normals.size()));
    for (std::size_t i = 0; i < normals.size(); ++i)
      array->SetTuple(static_cast<vtkIdType>(i), normals[i].data());
    poly->GetPointData()->SetNormals(array);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  // Each array inline (base64 in its DataArray element), no appended section: VTK reads an
  // appended section (raw or base64) by stopping its expat parser at <AppendedData>, which
  // expat's reparse deferral (expat 2.6, backported into Debian 12's security updates:
  // 2.5.0-1+deb12u5) defeats. Debian 12's ParaView 5.11 then fails on such files with "not
  // well-formed (invalid token)" (VTK issue 19258; seen with data/paraview/check_in_debian.sh).
  // Written to memory, then to the file atomically: VTK 9.1's inline mode crashes when the disk
  // fills mid-file (it frees position arrays only appended mode allocates).
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  // Level 1, not VTK's default 5: on the default film's 104 data sets (doubles and ids) the files
  // are 1.2 % larger (35.5 against 35.1 MB) for ~35 % fewer zlib samples under perf
  // (docs/benchmarks.md).
  writer->GetCompressor()->SetCompressionLevel(1);
  writer->WriteToOutputStringOn();
  const VtkMessages messages;  // VTK's own error lines go into the UserError, not to stderr
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw UserError(final_name(path).string(), "", "cannot write VTK PolyData" + messages.suffix());
  try {
    write_file_atomic(path, writer->GetOutputString());
  } catch (const UserError& e) {  // named as the file will be, not as it is staged
    throw UserError(final_name(path).string(), "", e.problem());
  }
}

PvdWriter::PvdWriter(fs::path pvd_path) : m_pvd(std::move(pvd_path)) {
  if (m_pvd.filename().empty()) throw UserError(m_pvd.string(), "", "not a file name");
  m_data_dir = m_pvd.parent_path() / (m_pvd.stem().string() + "_vtp");
  ensure_directory(m_pvd.parent_path());
  m_staging.emplace(m_data_dir);
}

PvdWriter::PvdWriter(fs::path pvd_path, fs::path write_dir)
    : m_pvd(std::move(pvd_path)), m_foreign_dir(std::move(write_dir)) {
  m_data_dir = m_pvd.parent_path() / (m_pvd.stem().string() + "_vtp");
}

fs::path PvdWriter::write_dir() const {
  if (m_staging) return m_staging->path();
  return m_foreign_dir.empty() ? m_data_dir : m_foreign_dir;
}

namespace {
std::string data_set_name(long step, int part) {
  char name[64];
  std::snprintf(name, sizeof name, "step_%06ld_%s.vtp", step, part_name(part));
  return name;
}
}  // namespace

void PvdWriter::add(long step, double time_s, SurfacePart part, const TriangleMesh* mesh,
                    const std::vector<PointScalars>& scalars) {
  write(step, part, mesh, scalars);
  record(step, time_s, part);
}

void PvdWriter::write(long step, SurfacePart part, const TriangleMesh* mesh,
                      const std::vector<PointScalars>& scalars) const {
  write_vtp(write_dir() / data_set_name(step, static_cast<int>(part)),
            mesh ? *mesh : TriangleMesh{}, mesh ? scalars : std::vector<PointScalars>{});
}

void PvdWriter::record(long step, double time_s, SurfacePart part) {
  const int p = static_cast<int>(part);
  const std::string rel = m_data_dir.filename().string() + "/" + data_set_name(step, p);
  // Replace an earlier entry for the same time and part (a re-meshed step), else append.
  auto same = [&](const Entry& e) { return e.part == p && e.file == rel; };
  auto it = std::find_if(m_entries.begin(), m_entries.end(), same);
  if (it != m_entries.end())
    it->time_s = time_s;
  else
    m_entries.push_back({time_s, p, rel});
  std::stable_sort(m_entries.begin(), m_entries.end(), [](const Entry& a, const Entry& b) {
    return a.time_s != b.time_s ? a.time_s < b.time_s : a.part < b.part;
  });
}

void PvdWriter::commit() {
  if (m_staging) {
    m_staging->commit();
    m_staging.reset();
  }
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
                      const ProgressCallback& progress, const StepPlacement& placement) {
  PvdSeriesOptions options;
  options.progress = progress;
  if (placement)
    options.placement = [&](const MeshedStep& s, const TriangleMesh*) { return placement(s.step); };
  write_pvd_series(simdir, out_pvd, options);
}

namespace {

// One step of the series: its surfaces read once, sampled, placed, written and handed to the
// caller's hook; returns where it was placed. Throws (the caller keeps the exception: this runs
// inside an OpenMP loop).
std::optional<std::array<double, 3>> write_series_step(const fs::path& simdir, const MeshedStep& s,
                                                       const PvdWriter& writer,
                                                       const PvdSeriesOptions& options) {
  char field_name[64];
  std::snprintf(field_name, sizeof field_name, "step_%06ld.grid", s.step);
  std::optional<sim::GridField> field;
  if (fs::exists(simdir / "fields" / field_name))
    field = sim::read_grid_field(simdir / "fields" / field_name);
  std::optional<TriangleMesh> mesh[2];
  for (const SurfacePart part : {SurfacePart::inner, SurfacePart::outer}) {
    const auto& file = part == SurfacePart::inner ? s.inner : s.outer;
    if (file) mesh[static_cast<int>(part)] = meshio::read_obj(*file);
  }
  const TriangleMesh* outer = mesh[1] ? &*mesh[1] : nullptr;
  const std::optional<std::array<double, 3>> offset =
      options.placement ? std::optional(options.placement(s, outer)) : std::nullopt;
  for (const SurfacePart part : {SurfacePart::inner, SurfacePart::outer}) {
    std::optional<TriangleMesh>& m = mesh[static_cast<int>(part)];
    if (!m) {
      writer.write(s.step, part, nullptr);
      if (options.surface) options.surface(s, part, nullptr);
      continue;
    }
    std::vector<PointScalars> scalars;
    if (field) {  // in the field's frame: before the placement
      PointScalars t{"temperature_c", {}};
      t.values.reserve(m->vertices.size());
      for (const auto& v : m->vertices) t.values.push_back(material_temperature_c(*field, v));
      scalars.push_back(std::move(t));
    }
    if (offset)
      for (auto& v : m->vertices)
        for (int k = 0; k < 3; ++k) v[k] += (*offset)[k];
    writer.write(s.step, part, &*m, scalars);
    if (options.surface) options.surface(s, part, &*m);
  }
  return offset;
}

// The series over the processes of options.farm (PvdSeriesOptions::farm). A step's offset
// travels to the leader as text ("+" and 17 digits: read back exactly; "+" alone without a
// placement); a failure travels as its outcome and is thrown on every process as it was.
StepOffsets write_series_on_farm(const fs::path& out_pvd, const fs::path& simdir,
                                 const SimulationFolder& folder, const PvdSeriesOptions& options) {
  WorkFarm& farm = *options.farm;
  // The leader stages the data sets' folder; every process learns how that went, then where, so
  // that none waits for a leader that has given up.
  std::optional<PvdWriter> writer;
  Outcome staged;
  if (farm.leader()) staged = Outcome::of([&] { writer.emplace(out_pvd); });
  farm.leaders_outcome(staged).rethrow();
  const std::string write_dir = farm.share(writer ? writer->write_dir().string() : "");
  if (!farm.leader()) writer.emplace(out_pvd, fs::path(write_dir));
  const auto total = static_cast<std::int64_t>(folder.steps.size());
  std::int64_t done = 0;
  Outcome progress_failure;
  const std::vector<std::string> texts = farm.run(
      total, options.threads,
      [&](long k) -> std::string {
        throw_if_interrupted();
        const auto offset =
            write_series_step(simdir, folder.steps[static_cast<std::size_t>(k)], *writer, options);
        char text[96] = "+";
        if (offset)
          std::snprintf(text, sizeof text, "+%.17g %.17g %.17g", (*offset)[0], (*offset)[1],
                        (*offset)[2]);
        return text;
      },
      [&] {  // on the leader, one call at a time (maybe on the farm's dispatcher thread, where
             // nothing may be thrown): an interrupt thrown here is thrown at the end
        ++done;
        if (options.progress && progress_failure.ok())
          progress_failure = Outcome::of([&] { options.progress(done, total); });
      });
  if (!farm.leader()) return {};
  progress_failure.rethrow();
  StepOffsets offsets;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    std::array<double, 3> offset{};
    if (std::sscanf(texts[i].c_str(), "+%lf %lf %lf", &offset[0], &offset[1], &offset[2]) == 3)
      offsets[folder.steps[i].step] = offset;
  }
  for (const MeshedStep& s : folder.steps)
    for (const SurfacePart part : {SurfacePart::inner, SurfacePart::outer})
      writer->record(s.step, s.time_s, part);
  writer->commit();
  return offsets;
}

}  // namespace

StepOffsets write_pvd_series(const fs::path& simdir, const fs::path& out_pvd,
                             const PvdSeriesOptions& options) {
  const SimulationFolder folder = read_simulation_folder(simdir);
  if (!folder.meshed)
    throw UserError((simdir / "mesh" / "manifest.json").string(), "",
                    "not found: mesh the simulation first (thaw mesh)");
  if (options.farm) return write_series_on_farm(out_pvd, simdir, folder, options);
  PvdWriter writer(out_pvd);
  std::vector<std::optional<std::array<double, 3>>> placed(folder.steps.size());
  const auto total = static_cast<std::int64_t>(folder.steps.size());
  std::vector<std::exception_ptr> failure(folder.steps.size());
  std::int64_t done = 0;
  // Steps are independent files; nothing may leave the loop by an exception.
#pragma omp parallel for schedule(dynamic, 1) \
    num_threads(options.threads > 0 ? options.threads : omp_get_max_threads())
  for (std::int64_t k = 0; k < total; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (interrupt_requested()) continue;  // thrown after the loop
    try {
      placed[i] = write_series_step(simdir, folder.steps[i], writer, options);
#pragma omp critical(thaw_pvd_series_progress)
      {
        ++done;
        try {
          if (options.progress) options.progress(done, total);
        } catch (...) {
          failure[i] = std::current_exception();
        }
      }
    } catch (...) {
      failure[i] = std::current_exception();
    }
  }
  throw_if_interrupted();
  for (const std::exception_ptr& e : failure)
    if (e) std::rethrow_exception(e);
  for (const MeshedStep& s : folder.steps)
    for (const SurfacePart part : {SurfacePart::inner, SurfacePart::outer})
      writer.record(s.step, s.time_s, part);
  writer.commit();
  StepOffsets offsets;
  for (std::size_t i = 0; i < placed.size(); ++i)
    if (placed[i]) offsets[folder.steps[i].step] = *placed[i];
  return offsets;
}

}  // namespace thaw::inspect
