#pragma once
// The view transform from scene radiance to a display ([image] tone): "clip" (the old mapping:
// exposed linear sRGB clamped to [0, 1], as POV-Ray; the comparison scenes keep it) or "agx", a
// filmic curve after Troy Sobotka's AgX (2022, the view transform of Blender 4), in the compact
// form of Benjamin Wrensch's "Minimal AgX implementation" (iolite engine blog, 2023): the colour
// is inset towards the achromatic axis by a 3x3 matrix, encoded as log2 exposure over
// [-12.47, +4.03] stops around 1, shaped by a sixth-order polynomial fit of AgX's sigmoid,
// outset again and decoded with gamma 2.2. Highlights roll off to white instead of clipping (a
// channel at 16x white is still below 1) and bright saturated colours desaturate as film does.
// Only display outputs (PNG) use it; PFM and EXR stay linear. Knows nothing about files.
#include "render/math/color.h"

namespace thaw::render {

enum class ViewTransform { clip, agx };

/// AgX of a linear sRGB colour (already exposed): display-referred linear sRGB in [0, 1], for the
/// sRGB encoder.
Rgb agx_view(const Rgb& linear);

/// AgX's curve on one channel, without the inset and outset matrices: the display value
/// (gamma-encoded, [0, 1]) that the adaptive film's error metric compares
/// (render/film/adaptive_pixel.h).
float agx_display_channel(float linear);

}  // namespace thaw::render
