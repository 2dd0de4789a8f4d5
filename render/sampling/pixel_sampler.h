#pragma once
// Deterministic low-discrepancy sample points per (pixel, sample index, dimension): the 2D
// Sobol (0,2)-sequence "padded" to any number of dimensions (pbrt-v4's PaddedSobolSampler idea,
// with Burley 2020's shuffling instead of a permutation of a fixed sample count):
//  - each dimension pair d of pixel (x, y) gets its own seed, hashed from (x, y, d, scene seed);
//  - the sample index is Owen-scrambled as an integer with that seed (digit k flipped as a
//    function of the more significant digits), so samples 0 .. 2^m - 1 of every pixel and
//    dimension are one aligned block of 2^m Sobol points: a (0,m,2)-net, for every m, which makes
//    the sequence progressive (adaptive sampling may stop after any power of two and stays
//    stratified) while different dimension pairs are decorrelated;
//  - each point is Owen-scrambled (independently per coordinate), which keeps the net property
//    and makes every point uniformly distributed.
// A point depends only on (pixel, index, dimension, seed): never on the thread, tile or call
// order. Knows nothing about images, cameras or lights.
#include <cstdint>

#include "render/sampling/owen_scramble.h"
#include "render/sampling/sobol.h"

namespace thaw::render::sampling {

struct Point2 {
  float x = 0, y = 0;
};

class PixelSampler {
 public:
  PixelSampler(int x, int y, std::uint64_t seed = 0)
      : m_x(static_cast<std::uint32_t>(x)), m_y(static_cast<std::uint32_t>(y)), m_seed(seed) {}

  /// Point `index` of dimension pair `dimension`, in [0, 1)^2.
  Point2 get_2d(std::uint32_t index, std::uint32_t dimension) const {
    const std::uint32_t h = hash_seed(m_x, m_y, dimension, m_seed);
    const std::uint32_t shuffled = owen_scramble_index(index, h);
    // Three independent scrambles (index, x, y) from one hash: the odd multipliers keep them
    // apart (LK's seed enters through both an add and a multiply, so distinct seeds suffice).
    return {
        fraction_to_float(owen_scramble(sobol_dimension0(shuffled), h * 0x68bc21ebu + 0x02e5be93u)),
        fraction_to_float(
            owen_scramble(sobol_dimension1(shuffled), h * 0x967a889bu + 0x1b2d3c4du))};
  }

  /// Point `index` of the 1D dimension `dimension` (its own sequence: van der Corput, shuffled
  /// and scrambled as above; dimensions are not shared with get_2d's).
  float get_1d(std::uint32_t index, std::uint32_t dimension) const {
    const std::uint32_t h = hash_seed(m_x, m_y, dimension ^ 0x80000000u, m_seed ^ 0x5bd1e995u);
    return fraction_to_float(
        owen_scramble(sobol_dimension0(owen_scramble_index(index, h)), h * 0x68bc21ebu + 1u));
  }

  /// Burley's shuffle: Owen scrambling of the index's bits (digit k flipped as a function of the
  /// digits above it), so that [0, 2^m) maps onto one aligned block of 2^m indices.
  static std::uint32_t owen_scramble_index(std::uint32_t index, std::uint32_t seed) {
    return owen_scramble(index, seed ^ 0xa511e9b3u);
  }

 private:
  std::uint32_t m_x, m_y;
  std::uint64_t m_seed;
};

}  // namespace thaw::render::sampling
