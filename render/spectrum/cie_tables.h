#pragma once
// Raw CIE tables (5 nm, 380-780 nm): the 1931 2-degree colour-matching functions and the D65
// illuminant. Data only; interpolation and colour maths live in render/spectrum/colour.h.
#include <array>
#include <cstddef>

namespace thaw::render::cie {

/// First tabulated wavelength [nm].
inline constexpr double kTableStartNm = 380.0;
/// Table spacing [nm].
inline constexpr double kTableStepNm = 5.0;
/// Rows: 380, 385, ..., 780 nm.
inline constexpr std::size_t kTableSize = 81;

/// CIE 1931 2-degree colour-matching functions x-bar, y-bar, z-bar (dimensionless, y-bar peak 1).
extern const std::array<double, kTableSize> kXBar;
extern const std::array<double, kTableSize> kYBar;
extern const std::array<double, kTableSize> kZBar;
/// CIE standard illuminant D65, relative spectral power (100 at 560 nm).
extern const std::array<double, kTableSize> kD65;

}  // namespace thaw::render::cie
