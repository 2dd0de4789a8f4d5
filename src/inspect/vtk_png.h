#pragma once
// Saving what a VTK render window shows as a PNG, atomically (temporary name + rename).
// Internal to src/inspect.
#include <filesystem>

class vtkRenderWindow;

namespace thaw::inspect {

/// Renders `window` once more and writes its colour buffer (RGB) to `out_png`; throws
/// thaw::UserError naming the file when it cannot be written.
void save_png(vtkRenderWindow* window, const std::filesystem::path& out_png);

}  // namespace thaw::inspect
