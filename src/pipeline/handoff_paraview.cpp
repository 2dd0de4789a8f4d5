#include "src/pipeline/handoff_paraview.h"

#include <cstdio>
#include <string>

#include "base/atomic_file.h"

namespace thaw::pipeline {

void write_paraview_state(const std::filesystem::path& path, const render::CameraDescription& c,
                          int width, int height) {
  const auto v = [](const std::array<double, 3>& a) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", a[0], a[1], a[2]);
    return std::string(buf);
  };
  char size[64], fov[48];
  std::snprintf(size, sizeof size, "[%d, %d]", width, height);
  std::snprintf(fov, sizeof fov, "%.17g", c.vertical_fov_deg);
  const std::string text =
      std::string() +
      "# thaw run's meshes in ParaView through the film's camera (written by thaw run;\n"
      "# docs/handoff.md). pvpython paraview_state.py [--screenshot PATH], or File > Load State.\n"
      "import os\n"
      "import sys\n"
      "from paraview.simple import *\n"
      "\n"
      "# The run folder: this file's folder's parent, else the current folder.\n"
      "RUN_DIR = os.getcwd()\n"
      "if '__file__' in globals():\n"
      "    RUN_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))\n"
      "reader = PVDReader(registrationName='meshes.pvd',\n"
      "                   FileName=os.path.join(RUN_DIR, 'meshes.pvd'))\n"
      "view = GetActiveViewOrCreate('RenderView')\n"
      "view.ViewSize = " +
      size +
      "\n"
      "display = Show(reader, view)\n"
      "view.CameraPosition = " +
      v(c.position) +
      "\n"
      "view.CameraFocalPoint = " +
      v(c.look_at) +
      "\n"
      "view.CameraViewUp = " +
      v(c.up) +
      "\n"
      "view.CameraViewAngle = " +
      fov +
      "  # vertical [degrees]\n"
      "view.CameraParallelProjection = 0\n"
      "Render(view)\n"
      "if '--screenshot' in sys.argv:\n"
      "    SaveScreenshot(sys.argv[sys.argv.index('--screenshot') + 1], view,\n"
      "                   ImageResolution=" +
      size + ")\n";
  write_file_atomic(path, text);
  // ParaView's camera configuration (pqCameraDialog's Save / Load).
  const auto property = [](const char* name, const double* values, int n) {
    std::string p = std::string("    <Property name=\"") + name + "\" id=\"1." + name +
                    "\" number_of_elements=\"" + std::to_string(n) + "\">\n";
    for (int i = 0; i < n; ++i) {
      char e[96];
      std::snprintf(e, sizeof e, "      <Element index=\"%d\" value=\"%.17g\"/>\n", i, values[i]);
      p += e;
    }
    return p + "    </Property>\n";
  };
  const std::string pvcc =
      "<?xml version=\"1.0\"?>\n"
      "<PVCameraConfiguration description=\"ParaView camera configuration\" version=\"1.0\">\n"
      "  <Proxy group=\"views\" type=\"RenderView\" id=\"1\" servers=\"21\">\n" +
      property("CameraPosition", c.position.data(), 3) +
      property("CameraFocalPoint", c.look_at.data(), 3) + property("CameraViewUp", c.up.data(), 3) +
      property("CenterOfRotation", c.look_at.data(), 3) +
      property("CameraViewAngle", &c.vertical_fov_deg, 1) +
      "  </Proxy>\n</PVCameraConfiguration>\n";
  write_file_atomic(path.parent_path() / "paraview_camera.pvcc", pvcc);
}

}  // namespace thaw::pipeline
