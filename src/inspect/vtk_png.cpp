#include "src/inspect/vtk_png.h"

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include "base/atomic_file.h"
#include "base/error.h"

namespace thaw::inspect {
namespace fs = std::filesystem;

void save_png(vtkRenderWindow* window, const fs::path& out_png) {
  ensure_directory(out_png.parent_path());
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  const fs::path temp = temporary_sibling(out_png);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(temp.c_str());
  writer->Write();
  std::error_code ec;
  if (writer->GetErrorCode() != 0 || !fs::exists(temp, ec) || fs::file_size(temp, ec) == 0) {
    fs::remove(temp, ec);
    throw UserError(out_png.string(), "", "cannot write PNG (folder not writable or disk full)");
  }
  fs::rename(temp, out_png, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw UserError(out_png.string(), "", "cannot rename into place: " + ec.message());
  }
}

}  // namespace thaw::inspect
