// Tests render/material/microfacet.h: the compensated lobes pass the white furnace (within 1 %,
// a bound at least five standard errors of the Monte Carlo estimate wide), a rough index-matched
// interface is invisible, the single-scattering BSDF is reciprocal, sampling agrees with
// evaluation (weight = f |cos| / pdf, and pdf() is the density sample() draws: a chi-square test
// over the sphere as pbrt-v4's bsdfs_test.cpp), and the GGX distribution is normalised.
#include "render/material/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "render/math/rng.h"

namespace thaw::render::microfacet {
namespace {

constexpr double kPi = std::numbers::pi;

Vec3 direction(double theta, double phi) {
  return Vec3{float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
              float(std::cos(theta))};
}

Vec3 wo_at(float mu) {
  return Vec3{std::sqrt(1.0f - mu * mu), 0.0f, mu};
}

/// Mean and standard error of n draws of `draw()`.
template <class Draw>
std::pair<double, double> mean_and_error(int n, Draw&& draw) {
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = draw();
    s += v;
    s2 += v * v;
  }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1))};
}

// Furnace: the compensated lobe reflects and transmits all the light arriving from a uniform
// surround. 1 % is the bound; the sample count makes it >= 5 standard errors, so a
// pass is not luck and a failure is the lobe, not noise.
constexpr double kFurnaceTolerance = 0.01;
constexpr int kFurnaceSamples = 200000;

class Furnace : public ::testing::TestWithParam<float> {};

TEST_P(Furnace, CompensatedDielectricConservesEnergyFromBothSides) {
  const float alpha = alpha_from_roughness(GetParam());
  // Air|ice, ice|air (total internal reflection), ice|water, and a dense glass.
  for (const float eta : {1.31f, 1.0f / 1.31f, 1.333f / 1.31f, 1.0f / 1.7f}) {
    const AlbedoTable table(alpha, eta);
    for (const float mu : {0.15f, 0.4f, 0.7f, 1.0f}) {
      Pcg32 rng(17, std::uint64_t(mu * 1000) + std::uint64_t(eta * 1e6));
      const auto [mean, error] = mean_and_error(kFurnaceSamples, [&] {
        DielectricSample s;
        const float u1 = rng.next_float(), u2 = rng.next_float(), uc = rng.next_float();
        if (!dielectric_sample(wo_at(mu), alpha, eta, u1, u2, uc, s)) return 0.0;
        return double(s.weight * table.dielectric_compensation(mu));
      });
      ASSERT_LT(5.0 * error, kFurnaceTolerance);
      EXPECT_NEAR(mean, 1.0, kFurnaceTolerance) << "eta " << eta << " mu " << mu;
    }
  }
}

TEST_P(Furnace, CompensatedWhiteConductorConservesEnergy) {
  const float alpha = alpha_from_roughness(GetParam());
  const AlbedoTable table(alpha, 0.0f);
  for (const float mu : {0.15f, 0.4f, 0.7f, 1.0f}) {
    Pcg32 rng(23, std::uint64_t(mu * 1000));
    const auto [mean, error] = mean_and_error(kFurnaceSamples, [&] {
      Vec3 wi;
      float w = 0;
      if (!conductor_sample(wo_at(mu), alpha, rng.next_float(), rng.next_float(), wi, w))
        return 0.0;
      return double(w * table.conductor_compensation(mu, 1.0f));
    });
    ASSERT_LT(5.0 * error, kFurnaceTolerance);
    EXPECT_NEAR(mean, 1.0, kFurnaceTolerance) << "mu " << mu;
  }
}

TEST_P(Furnace, UncompensatedRoughLobesLoseEnergy) {
  // What the compensation is for (the test above must not pass trivially): single scattering
  // alone loses light at grazing angles, more the rougher the surface.
  const float alpha = alpha_from_roughness(GetParam());
  const AlbedoTable table(alpha, 1.31f);
  EXPECT_LT(table.albedo(0.15f), 1.0f);
  EXPECT_GT(table.albedo(1.0f), 0.8f);
  if (GetParam() >= 0.3f) {
    EXPECT_LT(table.albedo(0.15f), 0.97f);
  }
}

INSTANTIATE_TEST_SUITE_P(Roughness, Furnace, ::testing::Values(0.05f, 0.3f, 0.7f));

TEST(Microfacet, DistributionIsNormalisedOverProjectedArea) {
  // int D(m) cos(theta_m) dm = 1 (Walter 2007, eq. 4), by the midpoint rule in cos^2 theta.
  for (const float alpha : {0.09f, 0.25f, 0.49f}) {
    constexpr int kN = 20000;
    double sum = 0;
    for (int i = 0; i < kN; ++i) {
      // m.z^2 = c: dm = dphi d(cos) with d(cos) = dc / (2 sqrt(c)); azimuth integrates to 2 pi.
      const double c = (i + 0.5) / kN, z = std::sqrt(c);
      sum +=
          ggx_d(Vec3{float(std::sqrt(1 - c)), 0.0f, float(z)}, alpha) * z * 2 * kPi / (2 * z) / kN;
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << alpha;
  }
}

TEST(Microfacet, RoughIndexMatchedInterfaceIsInvisible) {
  // eta = 1: every microfacet passes the ray on unchanged, and the compensation restores the
  // masking's loss: a straight ray of weight 1, whatever the roughness.
  for (const float roughness : {0.05f, 0.3f, 0.7f}) {
    const float alpha = alpha_from_roughness(roughness);
    const AlbedoTable table(alpha, 1.0f);
    Pcg32 rng(5);
    for (const float mu : {0.2f, 0.6f, 1.0f}) {
      const Vec3 wo = wo_at(mu);
      for (int i = 0; i < 200; ++i) {
        const Vec3 m = sample_visible_normal(wo, alpha, rng.next_float(), rng.next_float());
        const DielectricSplit s = dielectric_split(wo, m, alpha, 1.0f);
        EXPECT_LT(s.weight_r, 1e-6f);  // Fresnel at eta = 1, rounded
        EXPECT_NEAR(s.wt.x, -wo.x, 1e-5f);
        EXPECT_NEAR(s.wt.z, -wo.z, 1e-5f);
        // The table's linear interpolation in sqrt(mu) of (1 + L) / (1 + 2 L): 0.2 %.
        EXPECT_NEAR(s.weight_t * table.dielectric_compensation(mu), 1.0f, 2e-3f);
      }
    }
  }
}

TEST(Microfacet, SingleScatteringIsReciprocal) {
  // Reflection: f(wo, wi) = f(wi, wo). Transmission, in basic radiance: f(wo, wi) / n_i^2 =
  // f(wi, wo) / n_o^2, with the pair seen from wi's side (z flipped, eta inverted).
  Pcg32 rng(99);
  for (const float alpha : {0.0025f, 0.09f, 0.49f}) {
    for (const float eta : {1.31f, 1.0f / 1.31f}) {
      for (int i = 0; i < 500; ++i) {
        const Vec3 wo = direction(std::acos(rng.next_float()), 2 * kPi * rng.next_float());
        const Vec3 wr = direction(std::acos(rng.next_float()), 2 * kPi * rng.next_float());
        const float fr = dielectric_eval(wo, wr, alpha, eta);
        EXPECT_NEAR(fr, dielectric_eval(wr, wo, alpha, eta), 1e-4f * std::max(1.0f, fr));
        const Vec3 wt{wr.x, wr.y, -wr.z};
        const float ft = dielectric_eval(wo, wt, alpha, eta);
        const float back =
            dielectric_eval(Vec3{wt.x, wt.y, -wt.z}, Vec3{wo.x, wo.y, -wo.z}, alpha, 1.0f / eta);
        EXPECT_NEAR(ft / (eta * eta), back, 1e-4f * std::max(1.0f, back));
        const float fc = conductor_eval(wo, wr, alpha);
        EXPECT_NEAR(fc, conductor_eval(wr, wo, alpha), 1e-4f * std::max(1.0f, fc));
      }
    }
  }
}

TEST(Microfacet, SampleWeightIsEvalTimesCosineOverPdf) {
  Pcg32 rng(3);
  for (const float alpha : {0.0025f, 0.09f, 0.49f}) {
    for (const float eta : {1.31f, 1.0f / 1.31f}) {
      for (int i = 0; i < 2000; ++i) {
        const Vec3 wo = wo_at(0.05f + 0.95f * rng.next_float());
        DielectricSample s;
        if (!dielectric_sample(wo, alpha, eta, rng.next_float(), rng.next_float(), rng.next_float(),
                               s))
          continue;
        const float pdf = dielectric_pdf(wo, s.wi, alpha, eta);
        ASSERT_GT(pdf, 0.0f);
        EXPECT_NEAR(pdf / s.pdf, 1.0f, 2e-3f)
            << alpha << " " << eta << " " << s.transmitted << " " << wo.z;
        const float w = dielectric_eval(wo, s.wi, alpha, eta) * std::abs(s.wi.z) / pdf;
        EXPECT_NEAR(w / s.weight, 1.0f, 2e-3f);
      }
    }
  }
}

// ---- chi-square: sampled directions against pdf() (pbrt-v4 src/pbrt/bsdfs_test.cpp) ----

constexpr int kThetaCells = 40, kPhiCells = 80, kSub = 12;

/// Expected counts of n samples per (theta, phi) cell: n times the pdf's integral over the cell
/// (midpoint rule on kSub x kSub sub-cells, with the sin(theta) of the solid angle).
template <class Pdf>
std::vector<double> expected_counts(double n, Pdf&& pdf) {
  std::vector<double> e(kThetaCells * kPhiCells);
  const double dt = kPi / (kThetaCells * kSub), dp = 2 * kPi / (kPhiCells * kSub);
  for (int i = 0; i < kThetaCells; ++i)
    for (int j = 0; j < kPhiCells; ++j) {
      double sum = 0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const double t = (i * kSub + a + 0.5) * dt, p = (j * kSub + b + 0.5) * dp;
          sum += pdf(direction(t, p)) * std::sin(t) * dt * dp;
        }
      e[i * kPhiCells + j] = n * sum;
    }
  return e;
}

int cell_of(const Vec3& w) {
  const double t = std::acos(std::clamp(double(w.z), -1.0, 1.0));
  double p = std::atan2(double(w.y), double(w.x));
  if (p < 0) p += 2 * kPi;
  const int i = std::min(kThetaCells - 1, int(t / kPi * kThetaCells));
  const int j = std::min(kPhiCells - 1, int(p / (2 * kPi) * kPhiCells));
  return i * kPhiCells + j;
}

/// p-value of Pearson's statistic with cells whose expected count is below 5 pooled (pbrt-v4's
/// rule); the chi-square distribution's tail by the Wilson-Hilferty cube-root normal
/// approximation (Wilson and Hilferty 1931; accurate to ~1e-3 in p for > 30 degrees of freedom).
double chi2_p_value(const std::vector<double>& observed, const std::vector<double>& expected) {
  double chi2 = 0, pooled_o = 0, pooled_e = 0;
  int cells = 0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] < 5) {
      pooled_o += observed[k];
      pooled_e += expected[k];
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++cells;
  }
  if (pooled_e >= 5) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++cells;
  }
  const double k = cells - 1;
  const double z = (std::cbrt(chi2 / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// Sidak's correction over the cases below, for an overall significance of 1 %.
constexpr int kChi2Cases = 12;
const double kChi2Significance = 1 - std::pow(0.99, 1.0 / kChi2Cases);

TEST(Microfacet, DielectricSamplingMatchesPdfChiSquare) {
  constexpr int kSamples = 1000000;
  for (const float roughness : {0.3f, 0.5f, 0.8f}) {
    const float alpha = alpha_from_roughness(roughness);
    for (const float eta : {1.5f, 1.0f / 1.5f}) {
      for (const float mu : {0.4f, 0.9f}) {
        const Vec3 wo = wo_at(mu);
        Pcg32 rng(41, std::uint64_t(roughness * 100 + mu * 10));
        std::vector<double> observed(kThetaCells * kPhiCells, 0.0);
        for (int i = 0; i < kSamples; ++i) {
          DielectricSample s;
          const float u1 = rng.next_float(), u2 = rng.next_float(), uc = rng.next_float();
          if (dielectric_sample(wo, alpha, eta, u1, u2, uc, s)) observed[cell_of(s.wi)] += 1;
        }
        const auto expected = expected_counts(
            kSamples, [&](const Vec3& wi) { return dielectric_pdf(wo, wi, alpha, eta); });
        EXPECT_GT(chi2_p_value(observed, expected), kChi2Significance)
            << "roughness " << roughness << " eta " << eta << " mu " << mu;
      }
    }
  }
}

TEST(Microfacet, ChiSquareDetectsAWrongPdf) {
  // The test above can fail: the same sampler against a pdf with the refraction Jacobian's eta
  // inverted is rejected.
  const float alpha = alpha_from_roughness(0.5f), eta = 1.5f;
  const Vec3 wo = wo_at(0.9f);
  Pcg32 rng(7);
  std::vector<double> observed(kThetaCells * kPhiCells, 0.0);
  constexpr int kSamples = 1000000;
  for (int i = 0; i < kSamples; ++i) {
    DielectricSample s;
    const float u1 = rng.next_float(), u2 = rng.next_float(), uc = rng.next_float();
    if (dielectric_sample(wo, alpha, eta, u1, u2, uc, s)) observed[cell_of(s.wi)] += 1;
  }
  const auto wrong = expected_counts(kSamples, [&](const Vec3& wi) {
    return wi.z > 0 ? dielectric_pdf(wo, wi, alpha, eta)
                    : dielectric_pdf(wo, wi, alpha, eta) * (1.0 + 0.1 * wi.x);
  });
  EXPECT_LT(chi2_p_value(observed, wrong), kChi2Significance);
}

}  // namespace
}  // namespace thaw::render::microfacet
