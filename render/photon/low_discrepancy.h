#pragma once
// A deterministic low-discrepancy sequence for photon tracing: Halton points (one prime base per
// dimension) with FIXED random digit permutations (Kocis & Whiten 1997, "Computational
// investigations of low-discrepancy sequences", ACM TOMS 23(2); pbrt-v4 DigitPermutation and
// ScrambledRadicalInverse in src/pbrt/util/lowdiscrepancy.h). The permutations break the
// correlation between the higher prime bases and are drawn once from a fixed seed, so point i is
// the same in every run, frame and thread: a photon pass depends only on the scene. Knows nothing
// about rays or scenes.
#include <cstdint>

namespace thaw::render::photon {

class ScrambledHalton {
 public:
  /// Dimensions available (bases 2, 3, 5, ..., 19).
  static constexpr int kDimensions = 8;

  /// Coordinate `dimension` (0 <= dimension < kDimensions) of point `index`, in [0, 1).
  static double sample(std::uint64_t index, int dimension);

  /// The prime base of `dimension`.
  static int base(int dimension);
};

}  // namespace thaw::render::photon
