#include "src/pipeline/render_overrides.h"

#include <charconv>
#include <cstdio>

#include "base/error.h"
#include "render/scene/scene_rules.h"

namespace thaw::pipeline {
namespace {

std::optional<long long> whole_number(std::string_view s) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

}  // namespace

RenderOverrides parse_size_override(const std::string& text) {
  const auto x = text.find_first_of("xX");
  const auto fail = [&](const std::string& problem) { throw UserError("", "--size", problem); };
  if (x == std::string::npos)
    fail("expected WIDTHxHEIGHT in pixels, e.g. 640x480 (got \"" + text + "\")");
  const auto w = whole_number(std::string_view(text).substr(0, x));
  const auto h = whole_number(std::string_view(text).substr(x + 1));
  if (!w || !h) fail("expected WIDTHxHEIGHT in pixels, e.g. 640x480 (got \"" + text + "\")");
  // The scene file's rules for [image] width and height (render/scene/scene_rules.h).
  for (long long side : {*w, *h})
    if (const auto problem = render::image_side_problem(side)) fail(*problem);
  if (const auto problem = render::image_pixels_problem(*w, *h)) fail(*problem);
  RenderOverrides o;
  o.width = static_cast<int>(*w);
  o.height = static_cast<int>(*h);
  return o;
}

int checked_spp_override(long long spp) {
  // The scene file's rule for [render.image] samples_per_pixel (render/scene/scene_rules.h).
  if (const auto problem = render::samples_per_pixel_problem(spp))
    throw UserError("", "--spp", *problem);
  return static_cast<int>(spp);
}

double checked_fps_override(double fps) {
  if (const std::string problem = fps_problem(fps); !problem.empty())
    throw UserError("", "--fps", problem);
  return fps;
}

void apply_render_overrides(RunScenario& sc, const RenderOverrides& o) {
  std::string text;
  if (o.width && o.height) {
    sc.scene.image.width = *o.width;
    sc.scene.image.height = *o.height;
    text += "size=" + std::to_string(*o.width) + "x" + std::to_string(*o.height) + "\n";
  }
  if (o.samples_per_pixel) {
    sc.scene.image.samples_per_pixel = *o.samples_per_pixel;
    text += "samples_per_pixel=" + std::to_string(*o.samples_per_pixel) + "\n";
  }
  if (!text.empty()) {
    sc.render_text += "\n[command line]\n" + text;
    sc.image_overridden = true;
  }
  if (o.fps) {
    sc.film.playback_fps = *o.fps;
    char buf[64];
    std::snprintf(buf, sizeof buf, "\n[command line]\nfps=%.17g\n", *o.fps);
    sc.film_text += buf;
  }
}

}  // namespace thaw::pipeline
