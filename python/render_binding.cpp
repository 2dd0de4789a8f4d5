// thaw.render: a scene file (or scene TOML text) rendered as `thaw render` renders it, returned
// as the linear float32 image (H x W x 3, row 0 at the top) instead of a file: the NumPy array
// views the renderer's own pixels (no copy). Overrides are the command line's [image] flags,
// each checked by the rule of the file key it overrides (render/scene/scene_rules.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "python/bindings.h"
#include "python/blocking_call.h"
#include "render/format/scene_parser.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "render/scene/scene_rules.h"

namespace py = pybind11;

namespace thaw::python {
namespace {

/// The names of the overrides, as the keyword arguments of thaw.render.
const char* const kOverrides =
    "width, height, spp, max_depth, exposure, dispersion, dispersion_wavelengths, "
    "dispersion_resolution_nm, wavelength_pattern, threads";

template <typename T>
T value_of(const std::string& key, const py::handle& value, const char* what) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw UserError(
        "", key,
        std::string("must be ") + what + " (got " + py::repr(value).cast<std::string>() + ")");
  }
}

template <typename T, typename Rule>
T checked(const std::string& key, T value, Rule rule) {
  if (const auto problem = rule(value)) throw UserError("", key, *problem);
  return value;
}

/// The overrides applied to `image` as `thaw render`'s flags are (src/cli/command_render.cpp).
void apply_overrides(const py::dict& overrides, render::ImageSettings& image, int& threads) {
  bool size = false;
  for (const auto& [k, v] : overrides) {
    const std::string key = k.cast<std::string>();
    if (key == "width" || key == "height") {
      const int side =
          checked(key, value_of<int>(key, v, "an integer"), render::image_side_problem);
      (key == "width" ? image.width : image.height) = side;
      size = true;
    } else if (key == "spp") {
      image.samples_per_pixel =
          checked(key, value_of<int>(key, v, "an integer"), render::samples_per_pixel_problem);
    } else if (key == "max_depth") {
      image.max_depth =
          checked(key, value_of<int>(key, v, "an integer"), render::max_depth_problem);
    } else if (key == "exposure") {
      image.exposure = checked(key, value_of<double>(key, v, "a number"), render::exposure_problem);
    } else if (key == "dispersion") {
      image.dispersion = *render::dispersion_from_name(
          checked(key, value_of<std::string>(key, v, "a string"), render::dispersion_name_problem));
    } else if (key == "dispersion_wavelengths") {
      image.dispersion_wavelengths =
          checked(key, value_of<int>(key, v, "an integer"), render::dispersion_wavelengths_problem);
    } else if (key == "dispersion_resolution_nm") {
      image.dispersion_resolution_nm =
          checked(key, value_of<double>(key, v, "a number"), render::dispersion_resolution_problem);
    } else if (key == "wavelength_pattern") {
      image.wavelength_pattern = *render::wavelength_pattern_from_name(checked(
          key, value_of<std::string>(key, v, "a string"), render::wavelength_pattern_name_problem));
    } else if (key == "threads") {
      threads = value_of<int>(key, v, "an integer");
      if (threads < 1 || threads > 1024)
        throw UserError("", key,
                        "must be between 1 and 1024 (got " + std::to_string(threads) + ")");
    } else {
      throw UserError("", key, std::string("unknown override; the overrides: ") + kOverrides);
    }
  }
  if (size)
    if (const auto problem = render::image_pixels_problem(image.width, image.height))
      throw UserError("", overrides.contains("width") ? "width" : "height", *problem);
}

py::array render_scene(render::SceneDescription desc, const py::dict& overrides,
                       const py::object& progress) {
  int threads = 0;
  apply_overrides(overrides, desc.image, threads);
  auto result = std::make_unique<render::RenderResult>();
  *result = call_blocking(
      [&] {
        const render::Scene scene = render::build_scene(desc);
        render::RenderOptions options;
        options.threads = threads;
        const int tile = options.tile_size;
        const std::int64_t tiles = std::int64_t((desc.image.width + tile - 1) / tile) *
                                   ((desc.image.height + tile - 1) / tile);
        ProgressReporter bar("render", tiles, /*quiet=*/true);
        render::RenderResult r = render::render(scene, options, bar.callback());
        throw_if_interrupted();  // the render skipped its remaining tiles: no image
        return r;
      },
      progress);
  const render::Image& image = result->image;
  const py::ssize_t h = image.height(), w = image.width();
  const auto f = static_cast<py::ssize_t>(sizeof(float));
  const float* data = &image.pixels().data()->r;
  static_assert(sizeof(render::Rgb) == 3 * sizeof(float));
  // The array owns the render's result through a capsule: its pixels are the array's memory.
  py::capsule owner(result.release(),
                    [](void* p) { delete static_cast<render::RenderResult*>(p); });
  return py::array(py::dtype::of<float>(), std::vector<py::ssize_t>{h, w, 3},
                   std::vector<py::ssize_t>{3 * f * w, 3 * f, f}, data, owner);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "render_file",
      [](const std::filesystem::path& path, const py::dict& overrides, const py::object& progress) {
        return render_scene(render::parse_scene_file(path), overrides, progress);
      },
      py::arg("path"), py::arg("overrides"), py::arg("progress") = py::none());
  m.def(
      "render_text",
      [](const std::string& text, const std::string& source_name,
         const std::filesystem::path& base_dir, const py::dict& overrides,
         const py::object& progress) {
        return render_scene(render::parse_scene_string(text, source_name, base_dir), overrides,
                            progress);
      },
      py::arg("text"), py::arg("source_name"), py::arg("base_dir"), py::arg("overrides"),
      py::arg("progress") = py::none());
}

}  // namespace thaw::python
