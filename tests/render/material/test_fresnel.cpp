// Tests render/material/fresnel.h against published values (Hecht, Optics 5th ed., sec. 4.6),
// energy conservation R + T = 1 with T from the Fresnel transmission amplitudes, Snell's law and
// the critical angle; each polarisation from both sides of the air|ice and ice|water interfaces,
// through total internal reflection, and the reciprocity of the two sides.
#include "render/material/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

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

/// Reflectance and transmittance of the s and p polarisations for light going from index n1
/// into n2 at angle theta_i, from the complex amplitude coefficients (Born & Wolf, Principles of
/// Optics, sec. 1.5.2-1.5.4): cos(theta_t) = sqrt(1 - sin^2(theta_t)) taken complex, so total
/// internal reflection (sin theta_t > 1, cos theta_t imaginary, no transmitted power) needs no
/// special case. T = Re(n2 cos_t) / (n1 cos_i) |t|^2 (the beam-area and impedance factor).
struct Polarised {
  double rs, rp, ts, tp;
};
Polarised polarised(double n1, double n2, double theta_i) {
  using C = std::complex<double>;
  const double ci = std::cos(theta_i), si = std::sin(theta_i);
  const C ct = std::sqrt(C(1.0 - (n1 * si / n2) * (n1 * si / n2), 0.0));
  const C rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
  const C rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
  const C ts = 2 * n1 * ci / (n1 * ci + n2 * ct);
  const C tp = 2 * n1 * ci / (n2 * ci + n1 * ct);
  const double beam = (n2 * ct).real() / (n1 * ci);
  return {std::norm(rs), std::norm(rp), beam * std::norm(ts), beam * std::norm(tp)};
}

// The interfaces of a melting shell, each seen from both sides with the index of each side
// (physics.md: ice 1.31, water 1.333; air 1.000293, Ciddor at 589 nm).
struct Interface {
  const char* name;
  double n1, n2;  // from, to
};
constexpr Interface kInterfaces[] = {{"air|ice", 1.000293, 1.31},
                                     {"ice|air", 1.31, 1.000293},
                                     {"ice|water", 1.31, 1.333},
                                     {"water|ice", 1.333, 1.31}};

TEST(Fresnel, EachPolarisationConservesEnergyFromBothSidesOfEachInterface) {
  // Every 0.1 degree from 0 to 90: R_s + T_s = 1 and R_p + T_p = 1 (double, 1e-12); the
  // renderer's unpolarised reflectance is their mean (float evaluation: a few 1e-7 of values
  // O(1), 1e-6 absolute, plus the cancellation in cos_t = sqrt(1 - sin^2 t) near the critical
  // angle: sin^2 t carries ~3 float ulps (1.8e-7), so cos_t is off by 1.8e-7 / (2 cos_t), and
  // |dR / dcos_t| <= 4 n2 / (n1 cos_i) (the s wave at small cos_t; the p wave alike): with n2 / n1
  // <= 1.02 wherever cos_t is small, 4e-7 / (cos_t cos_i) more); beyond the critical angle both
  // polarisations reflect everything, and so must the renderer (exactly 1).
  for (const Interface& f : kInterfaces) {
    const double critical = f.n1 > f.n2 ? std::asin(f.n2 / f.n1) : 10.0;
    int tir = 0;
    for (int k = 0; k <= 900; ++k) {
      const double theta = std::min(k * kPi / 1800.0, kPi / 2 - 1e-9);
      const Polarised p = polarised(f.n1, f.n2, theta);
      EXPECT_NEAR(p.rs + p.ts, 1.0, 1e-12) << f.name << " " << k / 10.0 << " deg";
      EXPECT_NEAR(p.rp + p.tp, 1.0, 1e-12) << f.name << " " << k / 10.0 << " deg";
      const float r =
          fresnel_dielectric(static_cast<float>(std::cos(theta)), static_cast<float>(f.n2 / f.n1));
      if (theta > critical) {
        ++tir;
        EXPECT_NEAR(p.rs, 1.0, 1e-12) << f.name;
        EXPECT_NEAR(p.rp, 1.0, 1e-12) << f.name;
        EXPECT_EQ(r, 1.0f) << f.name << " " << k / 10.0 << " deg";
      } else {
        const double st = f.n1 * std::sin(theta) / f.n2;
        const double tol = 1e-6 + 4e-7 / (std::sqrt(1 - st * st) * std::cos(theta));
        EXPECT_NEAR(r, 0.5 * (p.rs + p.rp), tol) << f.name << " " << k / 10.0 << " deg";
      }
    }
    // total internal reflection only from the denser side: ice -> air beyond 49.8 deg, water ->
    // ice beyond 79.3 deg
    if (f.n1 > f.n2)
      EXPECT_EQ(tir, 900 - static_cast<int>(std::floor(critical * 1800 / kPi))) << f.name;
    else
      EXPECT_EQ(tir, 0) << f.name;
  }
  EXPECT_NEAR(std::asin(1.000293 / 1.31) * 180 / kPi, 49.78, 0.01);
  EXPECT_NEAR(std::asin(1.31 / 1.333) * 180 / kPi, 79.34, 0.01);
}

TEST(Fresnel, BothSidesOfAnInterfaceReflectAlikeAtSnellRelatedAngles) {
  // Stokes reciprocity: light arriving from n1 at theta_1 and from n2 at theta_2 (n1 sin theta_1
  // = n2 sin theta_2) is reflected alike, r' = -r for each polarisation (Hecht sec. 4.10). A
  // renderer that took the index of the wrong side (eta instead of 1 / eta on the way out) breaks
  // this at O(R) away from normal incidence and near the critical angle.
  for (const Interface& f : kInterfaces) {
    if (f.n1 > f.n2) continue;  // each pair once, from its rarer side
    for (int k = 0; k < 90; ++k) {
      const double t1 = k * kPi / 180.0;
      const double t2 = std::asin(f.n1 * std::sin(t1) / f.n2);
      const float r12 =
          fresnel_dielectric(static_cast<float>(std::cos(t1)), static_cast<float>(f.n2 / f.n1));
      const float r21 =
          fresnel_dielectric(static_cast<float>(std::cos(t2)), static_cast<float>(f.n1 / f.n2));
      // float rounding of two evaluations, 1e-6 each, plus the cancellation near grazing bounded
      // as in the test above: 4e-7 / (cos t1 cos t2)
      EXPECT_NEAR(r12, r21, 2e-6 + 4e-7 / (std::cos(t1) * std::cos(t2)))
          << f.name << " " << k << " deg";
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
