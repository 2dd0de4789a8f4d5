#pragma once
// The wavelengths one camera sample carries, with their sampling densities: hero-wavelength
// spectral sampling (Wilkie, Nawaz, Droske, Weidlich & Hanika 2014, "Hero Wavelength Spectral
// Sampling", CGF 33(4)). One hero wavelength is drawn in [380, 780] nm, the other
// kSpectrumSamples - 1 are rotations of it by equal steps of the range (wrapping around), so the
// set covers the spectrum evenly and every wavelength is marginally distributed like the hero.
// Interface after pbrt-v4's SampledWavelengths (src/pbrt/util/spectrum.h), including
// TerminateSecondary.
//
// Densities. With a non-uniform hero density p, wavelength j is the output of N strategies
// ("hero drawn from p, then rotated by -k steps"); combining them with the balance heuristic
// gives weight f(l_j) / sum_k p(l_k) for every j (the rotation pre-images of l_j are exactly the
// N carried wavelengths). We store pdf_j = (1/N) sum_k p(l_k), so the estimator of a spectral
// integral is always the plain average (1/N) sum_j f(l_j) / pdf_j, as in pbrt. After
// terminate_secondary() only the hero is left with pdf p(l_0) / N, so the same average becomes
// f(l_0) / p(l_0): the one-sample estimator, unbiased because l_0 was drawn from p.
//
// Knows nothing about colour or materials.
#include <cmath>

#include "render/spectrum/sampled_spectrum.h"

namespace thaw::render {

/// How the hero wavelength is drawn.
enum class HeroDensity {
  /// Uniform on [380, 780] nm: p = 1/400 per nm.
  uniform,
  /// p proportional to 1/cosh^2(0.0072 (l - 538 nm)), truncated to [380, 780] nm: roughly follows
  /// the eye's sensitivity so less effort goes to 380-420 and 700-780 nm (Radziszewski, Boryczko &
  /// Alda 2009, "An improved technique for full spectral rendering"; pbrt-v4
  /// SampleVisibleWavelengths). Lower colour noise per sample for most scenes.
  visible,
};

class SampledWavelengths {
 public:
  static constexpr double kRangeNm = kLambdaMaxNm - kLambdaMinNm;

  /// Hero-wavelength sample from one uniform number u in [0, 1).
  static SampledWavelengths sample(double u, HeroDensity density = HeroDensity::visible) {
    SampledWavelengths w;
    const double hero =
        density == HeroDensity::uniform ? kLambdaMinNm + u * kRangeNm : sample_visible_nm(u);
    double pdf_sum = 0;
    for (int i = 0; i < kSpectrumSamples; ++i) {
      double l = hero + i * (kRangeNm / kSpectrumSamples);
      if (l > kLambdaMaxNm) l -= kRangeNm;  // rotate within the range (Wilkie et al. eq. 6)
      w.m_lambda_nm[i] = static_cast<float>(l);
      const double p = hero_pdf(l, density);
      if (i == 0) w.m_hero_pdf = static_cast<float>(p);
      pdf_sum += p;
    }
    w.m_pdf = SampledSpectrum(static_cast<float>(pdf_sum / kSpectrumSamples));
    return w;
  }

  /// Fixed wavelengths with given densities (tests, `thaw materials`).
  static SampledWavelengths from(const SampledSpectrum& lambda_nm, const SampledSpectrum& pdf) {
    SampledWavelengths w;
    w.m_lambda_nm = lambda_nm;
    w.m_pdf = pdf;
    w.m_hero_pdf = pdf[0] * kSpectrumSamples;
    return w;
  }

  /// Density [1/nm] of the hero distribution at l (0 outside [380, 780] nm).
  static double hero_pdf(double lambda_nm, HeroDensity density) {
    if (lambda_nm < kLambdaMinNm || lambda_nm > kLambdaMaxNm) return 0;
    if (density == HeroDensity::uniform) return 1.0 / kRangeNm;
    const double c = std::cosh(kVisibleA * (lambda_nm - kVisibleCentreNm));
    return kVisibleA / (visible_tanh_span() * c * c);
  }

  /// Wavelength i [nm].
  float lambda_nm(int i) const { return m_lambda_nm[i]; }
  const SampledSpectrum& lambdas_nm() const { return m_lambda_nm; }
  /// Density used by the estimator for wavelength i [1/nm]; 0 once terminated.
  float pdf(int i) const { return m_pdf[i]; }
  const SampledSpectrum& pdf() const { return m_pdf; }

  /// Keep only the hero wavelength: call at the first refraction whose index depends on
  /// wavelength, where the other wavelengths would need their own directions. The radiance
  /// values of the secondary wavelengths must be ignored from here on (their pdf is 0, so the
  /// film estimator drops them). Idempotent.
  void terminate_secondary() {
    if (secondary_terminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) m_pdf[i] = 0;
    m_pdf[0] = m_hero_pdf / kSpectrumSamples;
  }
  bool secondary_terminated() const {
    for (int i = 1; i < kSpectrumSamples; ++i)
      if (m_pdf[i] != 0) return false;
    return true;
  }

 private:
  static constexpr double kVisibleA = 0.0072;        // [1/nm]
  static constexpr double kVisibleCentreNm = 538.0;  // [nm]
  static double visible_tanh_span() {
    static const double span = std::tanh(kVisibleA * (kLambdaMaxNm - kVisibleCentreNm)) -
                               std::tanh(kVisibleA * (kLambdaMinNm - kVisibleCentreNm));
    return span;
  }
  /// Inverse CDF of the truncated 1/cosh^2 density: the CDF is proportional to tanh.
  static double sample_visible_nm(double u) {
    static const double t0 = std::tanh(kVisibleA * (kLambdaMinNm - kVisibleCentreNm));
    const double l = kVisibleCentreNm + std::atanh(t0 + u * visible_tanh_span()) / kVisibleA;
    return std::fmin(std::fmax(l, kLambdaMinNm), kLambdaMaxNm);
  }

  SampledSpectrum m_lambda_nm;
  SampledSpectrum m_pdf;
  float m_hero_pdf = 0;
};

}  // namespace thaw::render
