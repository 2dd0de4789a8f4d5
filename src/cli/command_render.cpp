// `thaw render SCENE.toml -o OUT.png`: renders a scene file with the Whitted ray tracer
// (render/), with a progress bar on stderr and a one-paragraph summary. Parsing and help only.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "base/error.h"
#include "base/interrupt.h"
#include "base/progress.h"
#include "render/format/scene_parser.h"
#include "render/image/exr_io.h"
#include "render/image/image_io.h"
#include "render/integrator/aov_pass.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "render/scene/scene_rules.h"
#include "src/cli/commands.h"

namespace thaw::cli {
namespace {

struct RenderArgs {
  std::string scene, output;
  std::optional<int> width, height, spp, max_depth, threads, dispersion_wavelengths;
  int png_bits = 8;
  std::optional<double> exposure, dispersion_resolution_nm;
  std::optional<std::string> dispersion;
  std::optional<std::string> wavelength_pattern;
  bool quiet = false;
};

/// `value` unless the scene's own rule for the key it overrides (render/scene/scene_rules.h)
/// finds a problem, which is then reported against the flag, in the same words as in a file.
template <typename T, typename Rule>
T checked(const char* option, T value, Rule rule) {
  if (const auto problem = rule(value)) throw UserError("", option, *problem);
  return value;
}

int checked_threads(int threads) {
  if (threads < 1 || threads > 1024)
    throw UserError("", "--threads",
                    "must be between 1 and 1024 (got " + std::to_string(threads) + ")");
  return threads;
}

/// The [image] keys given on the command line, each checked by the file key's rule.
void apply_image_flags(const RenderArgs& a, render::ImageSettings& image) {
  if (a.width) image.width = checked("--width", *a.width, render::image_side_problem);
  if (a.height) image.height = checked("--height", *a.height, render::image_side_problem);
  if (const auto problem = render::image_pixels_problem(image.width, image.height))
    throw UserError("", a.width ? "--width" : "--height", *problem);
  if (a.spp) image.samples_per_pixel = checked("--spp", *a.spp, render::samples_per_pixel_problem);
  if (a.dispersion_wavelengths)
    image.dispersion_wavelengths = checked("--dispersion-wavelengths", *a.dispersion_wavelengths,
                                           render::dispersion_wavelengths_problem);
  if (a.dispersion)
    image.dispersion = *render::dispersion_from_name(
        checked("--dispersion", *a.dispersion, render::dispersion_name_problem));
  if (a.dispersion_resolution_nm)
    image.dispersion_resolution_nm =
        checked("--dispersion-resolution-nm", *a.dispersion_resolution_nm,
                render::dispersion_resolution_problem);
  if (a.wavelength_pattern)
    image.wavelength_pattern = *render::wavelength_pattern_from_name(checked(
        "--wavelength-pattern", *a.wavelength_pattern, render::wavelength_pattern_name_problem));
  if (a.max_depth)
    image.max_depth = checked("--max-depth", *a.max_depth, render::max_depth_problem);
  if (a.exposure) image.exposure = checked("--exposure", *a.exposure, render::exposure_problem);
}

void run_render(const RenderArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  render::check_output_path(a.output);  // fail before any work, never leave a partial file
  if (!render::valid_png_bits(a.png_bits))
    throw UserError("", "--png-bits", "must be 8 or 16 (got " + std::to_string(a.png_bits) + ")");
  render::SceneDescription desc = render::parse_scene_file(a.scene);
  apply_image_flags(a, desc.image);
  render::RenderOptions options;
  if (a.threads) options.threads = checked_threads(*a.threads);

  const render::Scene scene = render::build_scene(desc);
  const int tile = options.tile_size;
  const std::int64_t tiles =
      std::int64_t((desc.image.width + tile - 1) / tile) * ((desc.image.height + tile - 1) / tile);
  render::RenderResult result;
  {
    ProgressReporter progress("render", tiles, a.quiet);
    result = render::render(scene, options, progress.callback());
    progress.finish();
  }
  throw_if_interrupted();  // the render skipped its remaining tiles: write nothing
  if (render::is_exr_path(a.output)) {
    // The compositing layers come from their own primary-ray pass (render/integrator/aov_pass.h).
    const render::AovImage aovs = render::render_aovs(scene, options.threads);
    const render::ExrMetadata meta{
        a.scene,      std::nullopt, desc.image.samples_per_pixel, desc.image.exposure,
        std::nullopt, std::nullopt};
    render::write_exr(a.output, result.image, &aovs, meta);
  } else {
    render::write_image(a.output, result.image, desc.image.exposure, a.png_bits, desc.image.view);
  }
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!a.quiet) {
    const auto& st = result.stats;
    const auto& ss = scene.statistics();
    std::printf("thaw render: wrote %s (%dx%d, %d spp, depth %d)\n", a.output.c_str(),
                desc.image.width, desc.image.height, desc.image.samples_per_pixel,
                desc.image.max_depth);
    std::printf(
        "  scene: %zu triangles, %zu spheres, %zu boxes, %zu planes; BVH %zu nodes, depth %d, "
        "built in %.3f s\n",
        ss.triangles, ss.spheres, ss.boxes, ss.planes, ss.bvh_nodes, ss.bvh_depth,
        ss.build_seconds);
    std::printf("  rays traced: %llu in %.3f s on %d threads (%.2f Mrays/s); total time %.3f s\n",
                static_cast<unsigned long long>(st.rays), st.seconds, st.threads,
                st.rays_per_second * 1e-6, total);
    std::printf("  medium mismatches: %llu\n",
                static_cast<unsigned long long>(st.medium_mismatches));
    if (st.adaptive_refractions + st.split_refractions > 0)
      std::printf(
          "  dispersion: %llu refractions integrated over the spectrum (%d probe wavelengths, "
          "jumps to %.2f nm), %llu split into one ray per wavelength\n",
          static_cast<unsigned long long>(st.adaptive_refractions),
          desc.image.dispersion_wavelengths + 1, desc.image.dispersion_resolution_nm,
          static_cast<unsigned long long>(st.split_refractions));
    if (st.refined_samples > 0)
      std::printf("  dispersion: %llu camera samples traced at %d wavelengths\n",
                  static_cast<unsigned long long>(st.refined_samples),
                  desc.image.dispersion_wavelengths);
    if (st.caustic_photons > 0)
      std::printf("  caustics: %lld photons traced, %zu stored, in %.3f s\n", st.caustic_photons,
                  st.caustic_photons_stored, st.caustic_seconds);
    else if (desc.caustics.enabled)
      std::printf("  caustics: nothing to trace (no light or no dielectric that bends light)\n");
  }
}

}  // namespace

void register_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene file (TOML, see docs/render.md) to PNG (8- or 16-bit sRGB), PFM (linear "
      "float) or EXR (half RGBA with depth, normal and id layers) "
      "with the Whitted ray tracer: refraction through nested media, Fresnel, shadows.");
  cmd->add_option("scene", args->scene, "scene file (TOML)")->required();
  cmd->add_option("-o,--output", args->output,
                  "output image: .png (8- or 16-bit sRGB), .pfm (linear float) or .exr (linear "
                  "half RGBA + Z, N, id layers)")
      ->required();
  cmd->add_option("--width", args->width, "image width [pixels] (overrides [image] width)");
  cmd->add_option("--height", args->height, "image height [pixels] (overrides [image] height)");
  cmd->add_option("--spp", args->spp,
                  "samples per pixel, stratified (overrides [image] samples_per_pixel)");
  cmd->add_option(
      "--dispersion-wavelengths", args->dispersion_wavelengths,
      "wavelengths probed for fringes (adaptive) or traced (split) at a dispersive refraction "
      "(overrides [image] dispersion_wavelengths)");
  cmd->add_option(
      "--dispersion", args->dispersion,
      "adaptive, split or hero: how light is traced through dispersive refractions (overrides "
      "[image] dispersion)");
  cmd->add_option(
      "--dispersion-resolution-nm", args->dispersion_resolution_nm,
      "adaptive dispersion: width [nm] to which fringes' colour jumps are located (overrides "
      "[image] dispersion_resolution_nm)");
  cmd->add_option(
      "--wavelength-pattern", args->wavelength_pattern,
      "shared (the same wavelengths in every pixel: smooth fringes) or per_pixel (overrides "
      "[image] wavelength_pattern)");
  cmd->add_option("--max-depth", args->max_depth,
                  "levels of the ray tree, primary = 1 (overrides [image] max_depth)");
  cmd->add_option("--threads", args->threads, "render threads (default: all cores)");
  cmd->add_option("--exposure", args->exposure,
                  "PNG exposure [stops] (overrides [image] exposure)");
  cmd->add_option("--png-bits", args->png_bits,
                  "PNG bits per sample: 8 (default) or 16 (sRGB either way)");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress bar and no summary");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace thaw::cli
