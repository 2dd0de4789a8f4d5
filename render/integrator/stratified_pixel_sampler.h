#pragma once
// Where in a pixel its camera samples go: an m x m jittered grid when samples_per_pixel is a
// square, otherwise a Latin hypercube (one sample per row and per column stratum, columns in a
// random order); a single sample goes through the pixel centre (as POV-Ray). Each pixel draws
// from its own PCG32 stream (sequence = pixel index), so a pixel's samples do not depend on which
// thread renders it or in what order. The integrator may draw further numbers from the same
// stream (wavelengths) between positions. Knows nothing about scenes or radiance.
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "render/math/rng.h"

namespace thaw::render {

/// Fills p with 0..n-1 in a random order (Fisher-Yates, n - 1 draws from rng).
inline void shuffle_indices(std::vector<int>& p, Pcg32& rng) {
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<int>(i);
  for (std::size_t i = p.size(); i-- > 1;)
    std::swap(p[i], p[rng.next_u32() % static_cast<std::uint32_t>(i + 1)]);
}

class StratifiedPixelSampler {
 public:
  /// `samples` per pixel, `image_width` [pixels] to number the pixels, `seed` of the streams.
  StratifiedPixelSampler(int samples, int image_width, std::uint64_t seed)
      : m_samples(samples),
        m_width(image_width),
        m_seed(seed),
        m_grid(static_cast<int>(std::lround(std::sqrt(double(samples))))),
        m_square(m_grid * m_grid == samples),
        m_perm(static_cast<std::size_t>(samples)),
        m_rng(0) {}

  int samples() const { return m_samples; }

  /// Starts pixel (x, y): its own stream, and the Latin hypercube's column order if needed.
  void start_pixel(int x, int y) {
    m_rng = Pcg32(std::uint64_t(y) * std::uint64_t(m_width) + std::uint64_t(x), m_seed);
    if (!m_square && m_samples > 1) shuffle_indices(m_perm, m_rng);
  }

  /// Offset of sample s in [0, 1)^2 inside the current pixel (two draws when samples > 1).
  std::pair<float, float> position(int s) {
    if (m_samples == 1) return {0.5f, 0.5f};
    if (m_square) {
      const float sx = (float(s % m_grid) + m_rng.next_float()) / float(m_grid);
      const float sy = (float(s / m_grid) + m_rng.next_float()) / float(m_grid);
      return {sx, sy};
    }
    const float sx = (float(s) + m_rng.next_float()) / float(m_samples);
    const float sy =
        (float(m_perm[static_cast<std::size_t>(s)]) + m_rng.next_float()) / float(m_samples);
    return {sx, sy};
  }

  /// The current pixel's stream, for the integrator's own dimensions.
  Pcg32& rng() { return m_rng; }

 private:
  int m_samples, m_width;
  std::uint64_t m_seed;
  int m_grid;
  bool m_square;
  std::vector<int> m_perm;
  Pcg32 m_rng;
};

}  // namespace thaw::render
