#pragma once
// 64-bit FNV-1a over bytes (Fowler, Noll, Vo): the fingerprint of kept intermediate results
// (the meshers' resume caches). Cheap; not cryptographic: it detects changes, it does not resist
// forgery. Knows nothing of what is hashed.
#include <cstdint>
#include <string_view>

namespace thaw {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ULL;  // 0xcbf29ce484222325

/// FNV-1a of `bytes`, continuing from `hash` (the offset basis for a fresh hash).
constexpr std::uint64_t fnv1a_64(std::string_view bytes, std::uint64_t hash = kFnv1aOffset) {
  for (const char c : bytes) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  return hash;
}

}  // namespace thaw
