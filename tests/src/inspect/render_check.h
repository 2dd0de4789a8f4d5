#pragma once
// Helpers for the rendering tests: skip when no X can be had, and read a PNG back with VTK.
#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <filesystem>

#include "base/subprocess.h"
#include "src/inspect/virtual_display.h"

#define THAW_SKIP_WITHOUT_X()                                                  \
  do {                                                                         \
    if (!thaw::inspect::display_available() && !thaw::find_executable("Xvfb")) \
      GTEST_SKIP() << "no X display and no Xvfb (apt-get install xvfb)";       \
  } while (0)

namespace thaw::inspect::testing {

inline vtkSmartPointer<vtkImageData> read_png(const std::filesystem::path& png) {
  vtkNew<vtkPNGReader> reader;
  EXPECT_GT(reader->CanReadFile(png.c_str()), 0) << png;  // 3: "certainly PNG"
  reader->SetFileName(png.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// RGB of pixel (x, y), y counted from the bottom as VTK stores images.
inline std::array<int, 3> pixel(vtkImageData* image, int x, int y) {
  std::array<int, 3> rgb{};
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<int>(image->GetScalarComponentAsDouble(x, y, 0, c));
  return rgb;
}

}  // namespace thaw::inspect::testing
