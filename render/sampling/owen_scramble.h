#pragma once
// Hash-based Owen scrambling of 32-bit fixed-point numbers and of sequence indices (Burley 2020,
// "Practical Hash-based Owen Scrambling", JCGT 9(4); the hash is the Laine-Karras permutation
// (Laine & Karras 2011) with the stronger constants published by Nathan Vegdahl). Owen
// scrambling flips each binary digit as a random function of the digits before it, so every
// elementary interval is mapped onto an elementary interval of the same size: a (t,m,s)-net stays
// a (t,m,s)-net, and the scrambled points are uniformly distributed. Knows nothing about images.
#include <bit>
#include <cstdint>
#include <initializer_list>

namespace thaw::render::sampling {

inline std::uint32_t reverse_bits(std::uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

/// Laine-Karras style permutation: every output bit depends only on the input bits of lower
/// significance (products and sums carry upwards only), so it is a bijection on every suffix.
inline std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

/// Owen scrambling of a fixed-point fraction in [0, 2^32): digit k (from the most significant)
/// is flipped as a function of digits 1..k-1 and the seed.
inline std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(v), seed));
}

/// Mixes up to four words into one well-distributed 32-bit seed (a 64-bit finaliser, Stafford's
/// "Mix13" variant of MurmurHash3's fmix64).
inline std::uint32_t hash_seed(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
  std::uint64_t h = a * 0x9e3779b97f4a7c15ull;
  for (std::uint64_t w : {b, c, d}) {
    h ^= w + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  return static_cast<std::uint32_t>(h ^ (h >> 32));
}

}  // namespace thaw::render::sampling
