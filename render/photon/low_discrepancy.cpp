// Scrambled Halton points; see low_discrepancy.h.
#include "render/photon/low_discrepancy.h"

#include <array>
#include <cmath>
#include <vector>

#include "base/check.h"
#include "render/math/rng.h"

namespace thaw::render::photon {

namespace {

constexpr std::array<int, ScrambledHalton::kDimensions> kPrimes{2, 3, 5, 7, 11, 13, 17, 19};
/// Digits per dimension: enough that base^-digits < 2^-40 (finer than any float coordinate).
constexpr int kMaxDigits = 40;
/// The fixed scrambling seed (any constant; changing it changes every photon pass).
constexpr std::uint64_t kScrambleSeed = 0x7468617763617573ULL;  // "thawcaus"

struct Permutations {
  /// perm[dimension][digit position][digit value]
  std::array<std::vector<std::vector<std::uint8_t>>, ScrambledHalton::kDimensions> perm;
  std::array<int, ScrambledHalton::kDimensions> digits{};
  /// tail[dimension][k]: the value of digit positions k, k+1, ... when the index has no digits
  /// left there (all zero, permuted): sum_{j >= k} perm[j][0] b^-(j+1)
  std::array<std::vector<double>, ScrambledHalton::kDimensions> tail;

  Permutations() {
    for (int d = 0; d < ScrambledHalton::kDimensions; ++d) {
      const int b = kPrimes[static_cast<std::size_t>(d)];
      double scale = 1.0;
      int n = 0;
      while (scale > 0x1p-40 && n < kMaxDigits) {
        scale /= b;
        ++n;
      }
      digits[static_cast<std::size_t>(d)] = n;
      Pcg32 rng(static_cast<std::uint64_t>(d) + 1, kScrambleSeed);
      auto& pd = perm[static_cast<std::size_t>(d)];
      pd.resize(static_cast<std::size_t>(n));
      for (auto& p : pd) {
        p.resize(static_cast<std::size_t>(b));
        for (int k = 0; k < b; ++k) p[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(k);
        for (int k = b - 1; k > 0; --k)  // Fisher-Yates
          std::swap(p[static_cast<std::size_t>(k)],
                    p[rng.next_u32() % static_cast<std::uint32_t>(k + 1)]);
      }
      auto& t = tail[static_cast<std::size_t>(d)];
      t.assign(static_cast<std::size_t>(n) + 1, 0.0);
      for (int k = n - 1; k >= 0; --k)
        t[static_cast<std::size_t>(k)] =
            t[static_cast<std::size_t>(k) + 1] +
            pd[static_cast<std::size_t>(k)][0] * std::pow(double(b), -(k + 1));
    }
  }
};

const Permutations& permutations() {
  static const Permutations p;  // thread-safe initialisation (C++11 magic statics)
  return p;
}

}  // namespace

int ScrambledHalton::base(int dimension) {
  THAW_CHECK(dimension >= 0 && dimension < kDimensions, "Halton dimension out of range");
  return kPrimes[static_cast<std::size_t>(dimension)];
}

double ScrambledHalton::sample(std::uint64_t index, int dimension) {
  THAW_CHECK(dimension >= 0 && dimension < kDimensions, "Halton dimension out of range");
  const Permutations& p = permutations();
  const auto d = static_cast<std::size_t>(dimension);
  const std::uint64_t b = static_cast<std::uint64_t>(kPrimes[d]);
  const double inv_b = 1.0 / static_cast<double>(b);
  // Every digit position is permuted, the leading zeros beyond the index's length included
  // (otherwise the permutation of 0 would be lost and the points would cluster near 0).
  double value = 0.0, scale = inv_b;
  int k = 0;
  for (; k < p.digits[d] && index != 0; ++k) {
    const auto digit = static_cast<std::size_t>(index % b);
    index /= b;
    value += static_cast<double>(p.perm[d][static_cast<std::size_t>(k)][digit]) * scale;
    scale *= inv_b;
  }
  value += p.tail[d][static_cast<std::size_t>(k)];  // the remaining (zero) digits, permuted
  return value < 1.0 ? value : 0x1.fffffffffffffp-1;
}

}  // namespace thaw::render::photon
