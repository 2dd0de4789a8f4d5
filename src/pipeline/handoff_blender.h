#pragma once
// The hand-off of a run to Blender, ParaView and compositors, with the camera the frames were
// rendered with:
//   DIR/handoff/blender_scene.py  builds the run in Blender in one step (src/pipeline/
//                                 blender_scene.py with the run's description inside): one object
//                                 per surface whose mesh follows the frame, Principled BSDF
//                                 materials, the camera, the lights, the environment, the frame
//                                 range and rate (docs/handoff.md)
//   DIR/handoff/camera.json       the camera and its matrices (handoff_camera.h)
//   DIR/handoff/surfaces.json     every frame's surfaces: their files and placements (any tool)
//   DIR/handoff/environment.hdr   the sky or map baked in Blender's lat-long layout
//                                 (handoff_environment.h); none for a constant background
//   DIR/handoff/meshes/           the surfaces no other file of the run holds (the puddle:
//                                 puddle_NNNNNN.obj, world space); the shell's surfaces are the
//                                 mesh stage's own OBJ files, referred to with their placement,
//                                 so the run keeps one copy of them
//   DIR/handoff/paraview_state.py meshes.pvd seen through the same camera (pvpython or File >
//                                 Load State)
// Every frame's scene is frame_scene()'s (frame_scene.h), the one the renderer drew, so surfaces
// added there (the puddle) come along by themselves. Knows nothing about Blender beyond the
// script's data.
#include <filesystem>
#include <string>
#include <vector>

#include "src/mesh/mesh_series.h"
#include "src/pipeline/run_scenario.h"
#include "src/pipeline/water_budget.h"

namespace thaw::pipeline {

struct SceneHandoffInput {
  std::filesystem::path run_dir;
  /// the scenario with the camera the frames use (the framing camera when it sets none)
  const RunScenario* framed = nullptr;
  /// the mesh stage's folder (the step records' files are relative to it) and its records
  std::filesystem::path mesh_dir;
  const mesh::MeshManifest* meshes = nullptr;
  /// the water of each simulation step (water_budget.h), indexed by step
  const std::vector<WaterBudget>* water = nullptr;
  /// the stage that writes the hand-off, named when the script finds its files missing
  std::string stage = "inspect";
};

/// Blender's point-light power [W] for thaw light intensity `intensity` (render/scene/
/// scene_description.h: with inverse-square falloff the irradiance at distance d is I / d^2, and
/// thaw's matte surfaces reflect albedo * E, POV-Ray's convention). Cycles' point light of power
/// P has radiant intensity P / (4 pi) and its diffuse BSDF reflects albedo * E / pi, so the same
/// lit surface needs P = 4 pi^2 I. Without falloff (POV-Ray's) thaw's light is as bright at
/// every distance: it is matched at `reference_distance_m` (the camera's target), P = 4 pi^2 I d^2.
double blender_light_power_w(double intensity, bool inverse_square, double reference_distance_m);

/// Writes the files above (each atomically).
void write_scene_handoff(const SceneHandoffInput& input);

/// write_scene_handoff() for a run: the frames' camera (run_camera, frame_camera.h) and water
/// (water_budget.h) from the simulation's rows, as the render stage takes them.
void write_run_handoff(const std::filesystem::path& run_dir, const RunScenario& sc,
                       const std::vector<sim::InterfaceRecord>& rows,
                       const std::filesystem::path& mesh_dir, const mesh::MeshManifest& meshes,
                       const std::string& stage);

}  // namespace thaw::pipeline
