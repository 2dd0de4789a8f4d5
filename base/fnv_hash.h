#pragma once
// 64-bit FNV-1a (Fowler, Noll, Vo; http://www.isthe.com/chongo/tech/comp/fnv/): the one copy of
// the hash for every fingerprint and checksum in thaw (resume records, run manifests, the grid
// field file's checksum, the spectral tracer's chain signatures). Header-only and dependency-free,
// so the liftable cores (thaw_sim_core, thaw_render_core) may use it. Cheap; not cryptographic:
// it detects changes, it does not resist forgery. Knows nothing of what is hashed.
#include <cstdint>
#include <string_view>

namespace thaw {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ULL;  // 0xcbf29ce484222325
inline constexpr std::uint64_t kFnv1aPrime = 1099511628211ULL;          // 0x100000001b3

/// One FNV-1a step: xor `value` into `hash`, then multiply by the FNV prime. Over octets this is
/// FNV-1a; over whole 64-bit words (ids, float bits) it is the same mix used as a cheap
/// order-sensitive combiner, which is not FNV-1a of the words' bytes.
constexpr std::uint64_t fnv1a_64_step(std::uint64_t hash, std::uint64_t value) {
  return (hash ^ value) * kFnv1aPrime;
}

/// FNV-1a of `bytes`, continuing from `hash` (the offset basis for a fresh hash).
constexpr std::uint64_t fnv1a_64(std::string_view bytes, std::uint64_t hash = kFnv1aOffset) {
  for (const char c : bytes) hash = fnv1a_64_step(hash, static_cast<unsigned char>(c));
  return hash;
}

}  // namespace thaw
