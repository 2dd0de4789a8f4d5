#pragma once
// What the 3D view draws of a frame's scene besides the shell: the scenario's objects (spheres,
// boxes, planes as a finite square with their checker cells, OBJ meshes, the puddle), its lights
// (a small glyph at a point light, a translucent ball for a sphere light) and the camera the
// frame is rendered with. Made on the preview's worker thread from the same SceneDescription the
// preview renders (VTK pipelines brought up to date, mesh files read there), then only swapped
// into the view by the GUI thread. Knows nothing of Qt or the widgets.
#include <vtkActor.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>

#include <array>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/scene/scene_description.h"

namespace thaw::gui {

struct SceneProps {
  /// objects first (in the description's order, the shell's two surfaces left out), then lights
  std::vector<vtkSmartPointer<vtkActor>> actors;
  /// what each actor was made from: an actor of an equal key draws the same
  std::vector<std::string> actor_keys;
  /// each actor's texture (null: none) and the colour drawn instead of it while the view is
  /// drawn quick (the texture's mean)
  std::vector<vtkSmartPointer<vtkTexture>> textures;
  std::vector<std::array<double, 3>> quick_colors;
  std::size_t objects = 0, lights = 0;
  /// the frame's camera (scene units, degrees)
  render::CameraDescription camera;
  /// what the actors were made from (scene_props_key): equal keys draw the same
  std::string key;
  /// the preview request they belong to (PreviewRenderer::request's serial)
  std::uint64_t serial = 0;
};

/// Everything the actors of `desc` depend on (shapes, placements, colours, lights' positions
/// and sizes; not the camera, intensities or image settings), as text.
std::string scene_props_key(const render::SceneDescription& desc,
                            const std::vector<const render::TriangleMesh*>& skip);

/// The actors of `desc`'s objects and lights, leaving out the objects whose in-memory mesh is
/// among `skip` (the shell's surfaces, which the view draws from the step). An infinite plane is
/// drawn as a square about the point the camera looks at, large against the camera's distance.
/// Actors of `previous` whose key is unchanged are taken over. Reads mesh files (relative to
/// desc.base_dir); throws thaw::UserError if one cannot be read.
SceneProps make_scene_props(const render::SceneDescription& desc,
                            const std::vector<const render::TriangleMesh*>& skip,
                            const SceneProps* previous = nullptr);

}  // namespace thaw::gui
