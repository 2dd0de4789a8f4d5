#pragma once
// The SIMD instruction set the hot loops (BVH traversal, photon lookups) use, decided once per
// process at run time. The build targets baseline x86-64 (SSE2); functions marked
// THAW_TARGET_AVX2 are compiled for AVX2 as well and run only where the CPU (and the OS, which
// must save the 256-bit registers) supports it: GCC's __builtin_cpu_supports checks both.
// No FMA is enabled for them, so their arithmetic rounds exactly as the SSE paths' does.
// THAW_SIMD=sse2 in the environment forces the baseline paths, to check that they give the same
// images as the AVX2 ones on a machine that has both. Knows nothing about rendering.

#if defined(__x86_64__) && defined(__GNUC__) && defined(__SSE2__)
#define THAW_AVX2_DISPATCH 1
#define THAW_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define THAW_AVX2_DISPATCH 0
#define THAW_TARGET_AVX2
#endif

namespace thaw::render {

enum class SimdLevel { sse2, avx2 };

/// Whether this CPU and OS run AVX2 code (false where THAW_TARGET_AVX2 code is not compiled).
bool cpu_supports_avx2();

/// What this CPU supports, unless THAW_SIMD=sse2 asks for the baseline.
SimdLevel detect_simd_level();

/// detect_simd_level(), evaluated once.
inline SimdLevel simd_level() {
  static const SimdLevel level = detect_simd_level();
  return level;
}

}  // namespace thaw::render
