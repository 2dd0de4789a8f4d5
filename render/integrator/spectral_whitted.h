#pragma once
// Spectral Whitted ray tracing: the shading of render/integrator/whitted_shading.h instantiated
// for radiance carried at kSpectrumSamples wavelengths per camera sample, over the image loop of
// render/integrator/image_tile_integrator.h (hero-wavelength sampling, Wilkie et
// al. 2014; render/spectrum/sampled_wavelengths.h), so that dispersion (n(lambda), render/media)
// and Beer-Lambert absorption come out of the physics. RGB albedos are uplifted with Smits'
// method, light, ambient, emission and background colours become RGB illuminant spectra (white =
// D65), the film converts each sample with the CIE 1931 observer to linear sRGB.
// - Non-dispersive interfaces keep all wavelengths on one ray (one spectral ray per RGB ray).
// - At a refraction into or out of a dispersive medium the reflected branch keeps every
//   wavelength with its own Fresnel reflectance; the transmitted branch ([image] dispersion):
//   "adaptive" (default, where the throughput so far is the same at every wavelength): the
//   transmitted light is integrated over 380-780 nm directly. Chain signatures (what the
//   refracted light of one wavelength ends on) on a grid of wavelengths and bisection locate the
//   jumps of the spectrum (fringes); each segment between jumps is weighted by its exact
//   reference-spectrum integral times a ratio of traced lanes. Its XYZ goes to the film beside
//   the sampled spectrum: fringes without colour noise. "split": one ray per carried
//   wavelength, each refracted with its own n ([image] dispersion_wavelengths > 4 traces the
//   camera sample again with further packets). "hero": the hero wavelength only
//   (terminate_secondary() on a copy, result re-expressed in the caller's wavelengths).
// - [image] wavelength_pattern: the camera samples' wavelengths are the same stratified set in
//   every pixel ("shared", one offset per image from the seed) or drawn per pixel.
// - Every segment travelled inside an absorbing medium (also after total internal reflection)
//   keeps exp(-alpha(lambda) d), d in scene units taken as metres.
// Same determinism as the RGB path: per-pixel RNG streams, image independent of thread count.
// The dispersion machinery below is spectral-only; every ray it traces goes through the shared
// shading. Called by render() when Scene::spectral() is set; knows nothing about TOML or files.
#include <cstdint>

#include "render/integrator/whitted.h"
#include "render/math/vec3.h"
#include "render/photon/caustic_map.h"
#include "render/spectrum/sampled_spectrum.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render {

/// Spectral render of `scene` (same contract as render()): image in linear sRGB. `caustics`:
/// the frame's photon map (render() builds it), or null for none.
RenderResult render_spectral(const Scene& scene, const RenderOptions& options = {},
                             const ProgressCallback& progress = {},
                             const photon::CausticMap* caustics = nullptr);

/// Spectral radiance along one ray (for tests), traced as a primary ray starting in `medium`,
/// expressed in `wavelengths` (convert with spectrum_to_linear_srgb(L, wavelengths)). Dispersive
/// refractions follow the scene's [image] dispersion; with "adaptive" the light they integrate
/// over the spectrum goes to the film's XYZ side channel, not into the returned spectrum, so
/// single-ray tests through dispersive media use "split" or "hero".
SampledSpectrum trace_spectral_ray(const Scene& scene, const Ray& ray, std::uint32_t medium,
                                   const SampledWavelengths& wavelengths,
                                   RenderStats* stats = nullptr);

/// The transmitted direction the spectral integrator takes at a dielectric interface for
/// wavelength `lambda_nm`: unit incident `d`, unit normal `n` facing the incident side, indices
/// of the media on the incident and far side evaluated at lambda. False on total internal
/// reflection. (The integrator's own Snell step, exposed so tests can check it against optics.)
bool spectral_refraction(const Vec3& d, const Vec3& n, double n_from, double n_to, Vec3& out);

}  // namespace thaw::render
