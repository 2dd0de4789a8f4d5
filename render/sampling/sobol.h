#pragma once
// The first two dimensions of the Sobol sequence (Sobol 1967) as 32-bit fixed-point numbers: a
// (0,2)-sequence in base 2, i.e. every aligned block of 2^m consecutive points is a (0,m,2)-net
// (each of the 2^m elementary intervals of area 2^-m holds exactly one point). Dimension 0 is the
// van der Corput radical inverse; dimension 1 has the direction numbers of the primitive
// polynomial x + 1 (m_1 = 1, m_k = 2 m_{k-1} xor m_{k-1}; Joe & Kuo 2008). Knows nothing else.
#include <array>
#include <cstdint>

#include "render/sampling/owen_scramble.h"

namespace thaw::render::sampling {

namespace detail {
constexpr std::array<std::uint32_t, 32> sobol_dimension1_matrix() {
  std::array<std::uint32_t, 32> columns{};
  std::uint64_t m = 1;  // m_k, k = 1..32; v_k = m_k / 2^k as a 32-bit fraction
  for (int k = 1; k <= 32; ++k) {
    if (k > 1) m = (2 * m) ^ m;
    columns[static_cast<std::size_t>(k - 1)] = static_cast<std::uint32_t>(m << (32 - k));
  }
  return columns;
}
inline constexpr std::array<std::uint32_t, 32> kSobolDimension1 = sobol_dimension1_matrix();

/// The matrix-vector product over GF(2) byte by byte: entry [b][v] is the xor of the columns
/// 8b .. 8b + 7 selected by the bits of v. The scrambled indices of the pixel sampler have all
/// 32 bits random, so a bit loop took 32 unpredictable branches; this takes 4 lookups (4 KiB).
constexpr std::array<std::array<std::uint32_t, 256>, 4> sobol_dimension1_byte_tables() {
  std::array<std::array<std::uint32_t, 256>, 4> t{};
  for (std::size_t b = 0; b < 4; ++b)
    for (std::size_t v = 0; v < 256; ++v)
      for (std::size_t k = 0; k < 8; ++k)
        if (v & (std::size_t(1) << k)) t[b][v] ^= kSobolDimension1[8 * b + k];
  return t;
}
inline constexpr std::array<std::array<std::uint32_t, 256>, 4> kSobolDimension1Bytes =
    sobol_dimension1_byte_tables();
}  // namespace detail

/// Point `index` of Sobol dimension 0 (van der Corput), as a fraction * 2^32.
inline std::uint32_t sobol_dimension0(std::uint32_t index) {
  return reverse_bits(index);
}

/// Point `index` of Sobol dimension 1, as a fraction * 2^32.
inline std::uint32_t sobol_dimension1(std::uint32_t index) {
  const auto& t = detail::kSobolDimension1Bytes;
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^
         t[3][index >> 24];
}

/// A 32-bit fraction as a float in [0, 1): the top 24 bits, exact in a float's mantissa.
inline float fraction_to_float(std::uint32_t v) {
  return static_cast<float>(v >> 8) * 0x1p-24f;
}

}  // namespace thaw::render::sampling
