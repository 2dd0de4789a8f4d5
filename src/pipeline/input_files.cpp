#include "src/pipeline/input_files.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

fs::path against(const fs::path& base_dir, const fs::path& file) {
  return file.is_absolute() ? file : base_dir / file;
}

}  // namespace

std::vector<fs::path> simulation_input_files(const RunScenario& sc) {
  std::vector<fs::path> files;
  const sim::Shape& shape = sc.simulation.shape;
  // The parser resolved the paths against the scenario's folder (sim/format/scenario_file.cpp).
  if (shape.outer.kind == sim::ShapeKind::obj) files.emplace_back(shape.outer.file);
  if (shape.cavity && shape.cavity->kind == sim::ShapeKind::obj)
    files.emplace_back(shape.cavity->file);
  return files;
}

std::vector<fs::path> scene_input_files(const RunScenario& sc) {
  std::vector<fs::path> files;
  const render::EnvironmentDescription& env = sc.scene.environment;
  if (env.kind == render::EnvironmentDescription::Kind::latlong && !env.file.empty())
    files.push_back(against(sc.scene.base_dir, env.file));
  for (const auto& obj : sc.scene.objects)
    if (!obj.mesh_file.empty()) files.push_back(against(sc.scene.base_dir, obj.mesh_file));
  return files;
}

void add_input_files(ContentHash& hash, const std::vector<fs::path>& files) {
  for (const fs::path& f : files) hash.add_file(f);
}

}  // namespace thaw::pipeline
