#pragma once
// Importance sampling of an environment's directions by their radiance: the environment (any
// kind: constant, sky with panels, lat-long map) tabulated on a lat-long grid of cells in theta
// (from +y) and phi, each cell's weight its mean luminance times its solid angle (plus a floor of
// 1e-3 of the mean, so that every direction has a density), sampled as a piecewise-constant 2D
// distribution (marginal in theta, conditional in phi; PBR 4th ed. sec. A.5.6 / 12.5.2). Used by
// next-event estimation at scattering events (render/integrator/whitted_shading.h), which
// evaluates the environment's own radiance at the sampled direction: the table only decides
// where the samples go, so the estimate is unbiased at any resolution. Knows nothing about
// scenes or rays.
#include <cstdint>
#include <vector>

#include "render/light/environment.h"
#include "render/math/vec3.h"
#include "render/sampling/pixel_sampler.h"

namespace thaw::render {

class EnvironmentSampler {
 public:
  /// Tabulates `env` on `width` x `height` cells (phi x theta), each the mean of 2 x 2 points.
  explicit EnvironmentSampler(const Environment& env, int width = 256, int height = 128);

  /// False when the environment is black everywhere (nothing to sample).
  bool empty() const { return m_empty; }

  /// A unit direction for the unit-square point u and its solid-angle density [1/sr].
  Vec3 sample(sampling::Point2 u, float& pdf) const;

  /// The solid-angle density [1/sr] with which sample() draws unit direction d.
  float pdf(const Vec3& d) const;

 private:
  int m_width, m_height;
  bool m_empty = true;
  /// per cell (row-major, theta rows): the cell's weight / total; cumulative sums
  std::vector<float> m_cell_probability;
  std::vector<double> m_row_cdf;   ///< height + 1 values, 0 .. 1
  std::vector<double> m_cell_cdf;  ///< per row width + 1 values, 0 .. 1
};

}  // namespace thaw::render
