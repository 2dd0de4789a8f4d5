#include "src/pipeline/handoff_paraview.h"

#include <cstdio>
#include <string>

#include "base/atomic_file.h"

namespace thaw::pipeline {
namespace {

/// The state's lines that show fields.pvd's velocity as arrows (ParaView's Glyph on cell data:
/// one arrow per cell centre), following the meshes' time.
constexpr const char* kVelocityGlyphs =
    R"(# The water's velocity (fields.pvd, cell data velocity_m_s [m/s]) as arrows at the cell
# centres, the fastest as long as a twentieth of the fields' box, coloured by the speed.
fields = PVDReader(registrationName='fields.pvd', FileName=os.path.join(RUN_DIR, 'fields.pvd'))
fields.UpdatePipeline(fields.TimestepValues[-1] if fields.TimestepValues else 0.0)
bounds = fields.GetDataInformation().GetBounds()
extent = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
fastest = fields.CellData['velocity_m_s'].GetRange(-1)[1]
arrows = Glyph(registrationName='velocity', Input=fields, GlyphType='Arrow')
arrows.OrientationArray = ['CELLS', 'velocity_m_s']
arrows.ScaleArray = ['CELLS', 'velocity_m_s']
arrows.ScaleFactor = extent / 20.0 / fastest if fastest > 0 else 1.0
arrows.GlyphMode = 'All Points'
arrows_display = Show(arrows, view)
ColorBy(arrows_display, ('POINTS', 'velocity_m_s', 'Magnitude'))
)";

}  // namespace

void write_paraview_state(const std::filesystem::path& path, const render::CameraDescription& c,
                          int width, int height, bool velocity) {
  const auto v = [](const std::array<double, 3>& a) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", a[0], a[1], a[2]);
    return std::string(buf);
  };
  char size[64], fov[48];
  std::snprintf(size, sizeof size, "[%d, %d]", width, height);
  std::snprintf(fov, sizeof fov, "%.17g", c.vertical_fov_deg);
  // The script's text, with @SIZE@, @POSITION@, @FOCAL@, @UP@ and @FOV@ filled in below.
  std::string text =
      R"(# thaw run's meshes in ParaView through the film's camera (written by thaw run;
# docs/handoff.md). File > Load State, or with ParaView's Python:
#   pvpython paraview_state.py [--frame N] [--screenshot PATH] [--mask PATH]
# --frame N: the run's step N (default 0); --screenshot: the view as a PNG at the frames' size;
# --mask: the meshes' silhouette, white on black, unlit (the hand-off test compares it with the
# film's frame).
import os
import sys

try:
    import paraview.simple
    from paraview.simple import *
except ImportError:
    sys.stderr.write("thaw hand-off: this script needs ParaView's Python (paraview.simple, "
                     "ParaView 5.10 or newer)\n")
    sys.exit(2)


def fail(problem):
    sys.stderr.write('thaw hand-off: ' + problem + '\n')
    sys.exit(2)


def option(name, default=None):
    if name not in sys.argv:
        return default
    at = sys.argv.index(name)
    if at + 1 >= len(sys.argv):
        fail(name + ' needs a value')
    return sys.argv[at + 1]


# The run folder: this file's folder's parent, else the current folder.
RUN_DIR = os.getcwd()
if '__file__' in globals():
    RUN_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(RUN_DIR, 'meshes.pvd')
if not os.path.isfile(MESHES):
    fail(MESHES + ' is missing (the inspect stage of thaw run writes it)')
# paraview.simple resets the camera on a view's first render unless told not to: the camera
# set below must be the one that renders.
paraview.simple._DisableFirstRenderCameraReset()
reader = PVDReader(registrationName='meshes.pvd', FileName=MESHES)
view = GetActiveViewOrCreate('RenderView')
view.ViewSize = @SIZE@
view.OrientationAxesVisibility = 0
display = Show(reader, view)
@VELOCITY@view.CameraPosition = @POSITION@
view.CameraFocalPoint = @FOCAL@
view.CameraViewUp = @UP@
view.CameraViewAngle = @FOV@  # vertical [degrees]
view.CameraParallelProjection = 0

times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
try:
    frame = int(option('--frame', '0'))
except ValueError:
    fail('--frame needs a whole number')
if not 0 <= frame < len(times):
    fail('--frame %d is not a step of this run (0 to %d)' % (frame, len(times) - 1))
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = times[frame]
Render(view)
if option('--screenshot'):
    SaveScreenshot(option('--screenshot'), view, ImageResolution=@SIZE@)
if option('--mask'):
@MASK@    display.ColorArrayName = ['POINTS', '']
    display.AmbientColor = [1, 1, 1]
    display.DiffuseColor = [1, 1, 1]
    display.Ambient, display.Diffuse, display.Specular = 1.0, 0.0, 0.0
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    Render(view)
    SaveScreenshot(option('--mask'), view, ImageResolution=@SIZE@)
)";
  const auto fill = [&text](const std::string& mark, const std::string& value) {
    for (auto at = text.find(mark); at != std::string::npos; at = text.find(mark, at))
      text.replace(at, mark.size(), value);
  };
  fill("@SIZE@", size);
  fill("@POSITION@", v(c.position));
  fill("@FOCAL@", v(c.look_at));
  fill("@UP@", v(c.up));
  fill("@FOV@", fov);
  fill("@VELOCITY@", velocity ? kVelocityGlyphs : "");
  fill("@MASK@", velocity ? "    Hide(arrows, view)  # the meshes' silhouette alone\n" : "");
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
