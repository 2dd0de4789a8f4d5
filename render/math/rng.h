#pragma once
// A small, fast random number generator (PCG32, O'Neill 2014) seeded from a pixel index, so every
// pixel's samples are the same whatever thread renders it (determinism across thread counts).
#include <cstdint>
#include <utility>
#include <vector>

namespace thaw::render {

class Pcg32 {
 public:
  /// `sequence` selects an independent stream (e.g. the pixel index), `seed` the position in it.
  explicit Pcg32(std::uint64_t sequence, std::uint64_t seed = 0x853c49e6748fea9bULL) {
    m_state = 0u;
    m_inc = (sequence << 1u) | 1u;
    next_u32();
    m_state += seed;
    next_u32();
  }
  std::uint32_t next_u32() {
    const std::uint64_t old = m_state;
    m_state = old * 6364136223846793005ULL + m_inc;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1).
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

 private:
  std::uint64_t m_state, m_inc;
};

/// Fills p with 0..n-1 in a random order (Fisher-Yates, n - 1 draws from rng).
inline void shuffle_indices(std::vector<int>& p, Pcg32& rng) {
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<int>(i);
  for (std::size_t i = p.size(); i-- > 1;)
    std::swap(p[i], p[rng.next_u32() % static_cast<std::uint32_t>(i + 1)]);
}

}  // namespace thaw::render
