#pragma once
// Off-screen VTK pictures of surfaces: one panel per mesh set, edges shown, the inner surface
// (water|ice) opaque blue and the outer surface (ice|air) translucent, all panels sharing one
// camera so shrinking is visible. Rendering needs X: a DisplayLease (virtual_display.h) is taken,
// which starts Xvfb when no display is usable. Output PNGs are written atomically.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "src/inspect/surface_role.h"
#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

struct SceneSurface {
  TriangleMesh mesh;
  SurfaceRole role = SurfaceRole::single;
};

struct ScreenshotPanel {
  std::string label;                   ///< printed at the panel's top left (may hold newlines)
  std::vector<SceneSurface> surfaces;  ///< may be empty (everything vanished)
};

struct ScreenshotOptions {
  std::string title;        ///< printed above the panels
  int panel_size_px = 640;  ///< each panel is panel_size_px square
  bool edges = true;        ///< draw triangle edges
};

/// Renders `panels` side by side into `out_png`. Throws thaw::UserError if no X display can be
/// had (see DisplayLease) or the PNG cannot be written.
void write_screenshot(const std::vector<ScreenshotPanel>& panels,
                      const std::filesystem::path& out_png, const ScreenshotOptions& options = {});

/// One OBJ file, one panel (the OBJ is validated first).
void write_obj_screenshot(const std::filesystem::path& obj, const std::filesystem::path& out_png);

/// A simulation folder: `step` alone if given, else up to four steps evenly spread over the
/// meshed steps that still have a surface (first and last of those included). Throws UserError when
/// the folder is not meshed or `step` is not one of its meshed steps.
void write_simulation_screenshot(const std::filesystem::path& simdir,
                                 const std::filesystem::path& out_png,
                                 std::optional<long> step = std::nullopt);

}  // namespace thaw::inspect
