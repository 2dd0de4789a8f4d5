#include "render/scene/camera_keys.h"

#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

using C = CameraDescription;

const CameraKey kCameraKeys[] = {
    {"position", "Camera position", "m", "required",
     "where the camera is, each coordinate within 1e15 of the origin",
     VectorKey<C>{&C::position, false, true}},
    {"look_at", "Camera looks at", "m", "required",
     "the point it looks at, each coordinate within 1e15 of the origin",
     VectorKey<C>{&C::look_at, false, true}},
    {"up", "Camera up", "", "[0, 1, 0]", "unit vector, not parallel to the view",
     VectorKey<C>{&C::up, true, false}},
    {"vertical_fov_deg", "Vertical field of view", "deg", "required",
     "full vertical field of view, [0.001, 180) degrees",
     NumberKey<C>{&C::vertical_fov_deg, vertical_fov_problem, nullptr, true}},
    {"medium", "Camera medium", "", "inferred",
     "medium the camera is in; by default the one medium that is outside some interface and "
     "inside none",
     TextKey<C>{&C::medium}},
};

}  // namespace

std::span<const CameraKey> camera_keys() {
  return kCameraKeys;
}

}  // namespace thaw::render
