#pragma once
// The AOV pass: a cheap primary-ray pass beside the beauty render, for compositing layers
// (render/image/aov_image.h): depth, normal, object and medium ids from the first surface on the
// ray through each pixel centre, and the alpha: the pixel's coverage by geometry from 2 x 2
// stratified rays if the background is black, else 1.
// Only Scene::intersect and Scene::interaction: no shading, no secondary rays, no randomness (the
// result does not depend on the thread count). Not filtered: ids and depth must stay the exact
// values of one surface (a filtered id or depth at an edge names no object and no distance).
#include "render/image/aov_image.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// The AOVs of `scene` at its image size. `threads` = 0: the OpenMP default.
AovImage render_aovs(const Scene& scene, int threads = 0);

}  // namespace thaw::render
