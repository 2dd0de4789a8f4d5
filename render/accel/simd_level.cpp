// Run-time choice of the SIMD paths; see simd_level.h.
#include "render/accel/simd_level.h"

#include <cstdlib>
#include <cstring>

namespace thaw::render {

bool cpu_supports_avx2() {
#if THAW_AVX2_DISPATCH
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

SimdLevel detect_simd_level() {
  const char* forced = std::getenv("THAW_SIMD");
  if (forced != nullptr && std::strcmp(forced, "sse2") == 0) return SimdLevel::sse2;
  return cpu_supports_avx2() ? SimdLevel::avx2 : SimdLevel::sse2;
}

}  // namespace thaw::render
