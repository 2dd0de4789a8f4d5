#include "src/pipeline/render_overrides.h"

#include <charconv>
#include <cstdio>

#include "render/scene/scene_parser.h"
#include "src/common/error.h"

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
  for (long long side : {*w, *h})
    if (side < 1 || side > render::kMaxImageSide)
      fail("each side must be between 1 and " + std::to_string(render::kMaxImageSide) +
           " pixels (got \"" + text + "\")");
  if (*w * *h > render::kMaxImagePixels)
    fail("image has too many pixels (limit " + std::to_string(render::kMaxImagePixels) + ")");
  RenderOverrides o;
  o.width = static_cast<int>(*w);
  o.height = static_cast<int>(*h);
  return o;
}

int checked_spp_override(long long spp) {
  // The scene parser's range for [render.image] samples_per_pixel (scene_parser.cpp).
  if (spp < 1 || spp > render::kMaxSamplesPerPixel)
    throw UserError("", "--spp",
                    "must be between 1 and " + std::to_string(render::kMaxSamplesPerPixel) +
                        " (got " + std::to_string(spp) + ")");
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
  if (!text.empty()) sc.render_text += "\n[command line]\n" + text;
  if (o.fps) {
    sc.film.playback_fps = *o.fps;
    char buf[64];
    std::snprintf(buf, sizeof buf, "\n[command line]\nfps=%.17g\n", *o.fps);
    sc.film_text += buf;
  }
}

}  // namespace thaw::pipeline
