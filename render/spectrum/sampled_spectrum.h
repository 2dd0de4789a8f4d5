#pragma once
// A spectral quantity (radiance, reflectance, transmittance, index of refraction) evaluated at
// the kSpectrumSamples wavelengths carried by one camera sample (pbrt-v4 SampledSpectrum,
// src/pbrt/util/spectrum.h). A tiny value type: element-wise arithmetic only. Which wavelengths
// the values belong to is SampledWavelengths' business (render/spectrum/sampled_wavelengths.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace thaw::render {

/// Wavelengths carried per camera sample. Four is pbrt-v4's default and what Wilkie et al. 2014
/// found a good trade-off between colour noise and cost; changing it only changes this number.
inline constexpr int kSpectrumSamples = 4;

/// Rendered spectral range [nm] (the 380-780 nm; the CIE 1931 tables are zero-ish
/// beyond it and every material table must cover it).
inline constexpr double kLambdaMinNm = 380.0;
inline constexpr double kLambdaMaxNm = 780.0;

class SampledSpectrum {
 public:
  constexpr SampledSpectrum() = default;
  /// Every sample set to `value`.
  constexpr explicit SampledSpectrum(float value) { m_values.fill(value); }
  constexpr explicit SampledSpectrum(const std::array<float, kSpectrumSamples>& values)
      : m_values(values) {}

  constexpr float operator[](int i) const { return m_values[static_cast<std::size_t>(i)]; }
  constexpr float& operator[](int i) { return m_values[static_cast<std::size_t>(i)]; }

  constexpr SampledSpectrum& operator+=(const SampledSpectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] += o[i];
    return *this;
  }
  constexpr SampledSpectrum& operator-=(const SampledSpectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] -= o[i];
    return *this;
  }
  constexpr SampledSpectrum& operator*=(const SampledSpectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] *= o[i];
    return *this;
  }
  constexpr SampledSpectrum& operator*=(float s) {
    for (auto& v : m_values) v *= s;
    return *this;
  }
  /// Element-wise division; a zero divisor gives zero (pbrt-v4 SafeDiv), so terminated
  /// wavelengths (pdf 0) drop out instead of producing NaN.
  constexpr SampledSpectrum& operator/=(const SampledSpectrum& o) {
    for (int i = 0; i < kSpectrumSamples; ++i) (*this)[i] = o[i] != 0 ? (*this)[i] / o[i] : 0.0f;
    return *this;
  }

  constexpr bool is_black() const {
    for (float v : m_values)
      if (v != 0) return false;
    return true;
  }
  /// Largest sample: the weight used to prune the Whitted tree.
  constexpr float max_component() const {
    float m = m_values[0];
    for (float v : m_values) m = std::max(m, v);
    return m;
  }
  constexpr float min_component() const {
    float m = m_values[0];
    for (float v : m_values) m = std::min(m, v);
    return m;
  }
  constexpr float average() const {
    float s = 0;
    for (float v : m_values) s += v;
    return s / kSpectrumSamples;
  }
  const std::array<float, kSpectrumSamples>& values() const { return m_values; }

 private:
  std::array<float, kSpectrumSamples> m_values{};
};

constexpr SampledSpectrum operator+(SampledSpectrum a, const SampledSpectrum& b) {
  return a += b;
}
constexpr SampledSpectrum operator-(SampledSpectrum a, const SampledSpectrum& b) {
  return a -= b;
}
constexpr SampledSpectrum operator*(SampledSpectrum a, const SampledSpectrum& b) {
  return a *= b;
}
constexpr SampledSpectrum operator*(SampledSpectrum a, float s) {
  return a *= s;
}
constexpr SampledSpectrum operator*(float s, SampledSpectrum a) {
  return a *= s;
}
constexpr SampledSpectrum operator/(SampledSpectrum a, const SampledSpectrum& b) {
  return a /= b;
}
constexpr bool operator==(const SampledSpectrum& a, const SampledSpectrum& b) {
  for (int i = 0; i < kSpectrumSamples; ++i)
    if (a[i] != b[i]) return false;
  return true;
}

/// Element-wise exp (Beer-Lambert: exp(-alpha * d) per wavelength). Not called `exp` so that an
/// unqualified exp(double) inside namespace thaw::render still finds std::exp.
inline SampledSpectrum exp_elementwise(const SampledSpectrum& s) {
  SampledSpectrum r;
  for (int i = 0; i < kSpectrumSamples; ++i) r[i] = std::exp(s[i]);
  return r;
}

}  // namespace thaw::render
