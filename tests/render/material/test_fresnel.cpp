// Tests render/material/fresnel.h against published values (Hecht, Optics 5th ed., sec. 4.6),
// energy conservation R + T = 1 with T from the Fresnel transmission amplitudes, Snell's law and
// the critical angle.
#include "render/material/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Float evaluation of a handful of operations on values O(1): relative error a few 1e-7;
// 1e-6 absolute on a reflectance in [0, 1] covers it.
constexpr float kTol = 1e-6f;

TEST(Fresnel, NormalIncidenceMatchesClosedForm) {
  // R0 = ((n1 - n2) / (n1 + n2))^2: air|glass 1.5 -> 0.04 (Hecht eq. 4.67), air|water -> 0.02006,
  // ice|water (1.31 | 1.33) -> 5.8e-5.
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, kTol);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.33f), 0.0200593f, kTol);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.33f / 1.31f), std::pow((1.33 - 1.31) / (1.33 + 1.31), 2),
              kTol);
  // Reciprocity at normal incidence.
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f / 1.5f), 0.04f, kTol);
}

TEST(Fresnel, BrewsterAngleLeavesOnlySPolarisation) {
  // At theta_B = atan(n) r_p = 0, so R = Rs / 2 with Rs = sin^2(theta_i - theta_t) /
  // sin^2(theta_i + theta_t) (Hecht eq. 4.42); for n = 1.5, theta_B = 56.31 deg, Rs = 0.1479,
  // R = 0.0740.
  const double tb = std::atan(1.5);
  const double tt = std::asin(std::sin(tb) / 1.5);
  const double rs = std::pow(std::sin(tb - tt) / std::sin(tb + tt), 2);
  EXPECT_NEAR(rs, 0.1479, 1e-4);
  EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(tb)), 1.5f), rs / 2, kTol);
}

TEST(Fresnel, ReflectancePlusTransmittanceIsOne) {
  // T from the transmission amplitudes t_s, t_p (Hecht eqs. 4.43, 4.45) times the beam-area and
  // impedance factor n_t cos t / (n_i cos i): a formula independent of the one under test.
  for (const double eta : {1.5, 1.31, 1.33 / 1.31, 1.0 / 1.5, 1.31 / 1.33}) {
    for (int k = 0; k < 90; ++k) {
      const double ti = k * kPi / 180.0;
      const double ci = std::cos(ti), si = std::sin(ti);
      const double st = si / eta;
      if (st >= 1.0) continue;
      const double ct = std::sqrt(1 - st * st);
      const double ts = 2 * ci / (ci + eta * ct), tp = 2 * ci / (eta * ci + ct);
      const double t = eta * ct / ci * 0.5 * (ts * ts + tp * tp);
      EXPECT_NEAR(fresnel_dielectric(static_cast<float>(ci), static_cast<float>(eta)) + t, 1.0,
                  1e-5)
          << "eta " << eta << " angle " << k;
    }
  }
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
  // Water -> ice: critical angle asin(1.31 / 1.33) = 80.05 deg.
  const double eta = 1.31 / 1.33;
  const double critical = std::asin(eta);
  EXPECT_NEAR(critical * 180 / kPi, 80.05, 0.01);
  EXPECT_EQ(
      fresnel_dielectric(static_cast<float>(std::cos(critical + 1e-3)), static_cast<float>(eta)),
      1.0f);
  EXPECT_LT(
      fresnel_dielectric(static_cast<float>(std::cos(critical - 1e-2)), static_cast<float>(eta)),
      1.0f);
}

TEST(Snell, RefractedDirectionObeysSnellAndStaysInPlane) {
  for (const float eta : {1.5f, 1.31f, 1.0f / 1.33f}) {
    for (int k = 0; k < 89; k += 4) {
      const float ti = static_cast<float>(k * kPi / 180.0);
      const Vec3 d{std::sin(ti), -std::cos(ti), 0};
      const Vec3 n{0, 1, 0};
      Vec3 t;
      const bool ok = refract(d, n, eta, t);
      const float st = std::sin(ti) / eta;
      if (st >= 1.0f) {
        EXPECT_FALSE(ok);
        continue;
      }
      ASSERT_TRUE(ok);
      EXPECT_NEAR(length(t), 1.0f, 1e-6f);
      EXPECT_NEAR(t.x, st, 1e-6f);  // sin(theta_t) = sin(theta_i) / eta
      EXPECT_LT(t.y, 0.0f);         // continues through the surface
      EXPECT_EQ(t.z, 0.0f);         // plane of incidence
    }
  }
}

TEST(Snell, CriticalAngleBoundary) {
  const float eta = 1.0f / 1.5f;  // glass -> air, critical angle asin(1/1.5) = 41.81 deg
  const float tc = std::asin(eta);
  Vec3 t;
  EXPECT_TRUE(refract(Vec3{std::sin(tc - 1e-3f), -std::cos(tc - 1e-3f), 0}, {0, 1, 0}, eta, t));
  EXPECT_FALSE(refract(Vec3{std::sin(tc + 1e-3f), -std::cos(tc + 1e-3f), 0}, {0, 1, 0}, eta, t));
}

}  // namespace
}  // namespace thaw::render
