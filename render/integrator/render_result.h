#pragma once
// What a render takes besides the scene (threads, tile size, seed) and what it returns: the linear
// image and its statistics. Shared by every integrator; knows nothing about how they trace.
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "render/image/image.h"

namespace thaw::render {

struct RenderOptions {
  /// OpenMP threads; 0 = the OpenMP default (all cores)
  int threads = 0;
  /// square tile side [pixels]
  int tile_size = 16;
  /// seed of the per-pixel jitter streams
  std::uint64_t seed = 0;
  /// set from another thread to stop early (an interactive preview restarted by an edit): the
  /// tiles not yet started are skipped and the returned image is incomplete
  const std::atomic<bool>* cancel = nullptr;
};

struct RenderStats {
  /// camera, reflected, refracted and shadow rays
  std::uint64_t rays = 0;
  /// camera samples taken by the film (adaptive anti-aliasing: between min_samples and the cap
  /// per pixel)
  std::uint64_t camera_samples = 0;
  /// rays that reached an interface from a side whose medium differs from the one they carry
  std::uint64_t medium_mismatches = 0;
  /// spectral mode: camera samples traced with all [image] dispersion_wavelengths (split)
  std::uint64_t refined_samples = 0;
  /// spectral mode: dispersive refractions integrated over the spectrum (adaptive) and split
  /// into one ray per carried wavelength (split, or adaptive's fallback)
  std::uint64_t adaptive_refractions = 0, split_refractions = 0;
  /// caustics (render/photon): photons traced and stored by the frame's photon pass, and its
  /// wall time [s] (before the tracing, not included in `seconds`)
  long long caustic_photons = 0;
  std::size_t caustic_photons_stored = 0;
  double caustic_seconds = 0;
  /// wall time of the tracing [s]
  double seconds = 0;
  double rays_per_second = 0;
  int threads = 0;
};

struct RenderResult {
  /// linear radiance, scene.settings().width x height
  Image image;
  RenderStats stats;
};

}  // namespace thaw::render
