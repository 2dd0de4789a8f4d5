// CIE colour matching and sRGB: chromaticities of equal-energy white and D65, the sRGB white
// point, and the unit-luminance normalisation of the D65 illuminant.
#include <gtest/gtest.h>

#include "render/spectrum/cie_tables.h"
#include "render/spectrum/colour.h"

namespace thaw::render {
namespace {

/// Dense midpoint quadrature of spectrum(l) * cmf(l) over 380-780 nm at 0.01 nm.
template <class F>
Xyz integrate(F spectrum) {
  Xyz r;
  const double h = 0.01;
  for (double l = kLambdaMinNm + h / 2; l < kLambdaMaxNm; l += h) {
    const Xyz b = cie_xyz_bar(l);
    const double s = spectrum(l) * h;
    r.x += s * b.x;
    r.y += s * b.y;
    r.z += s * b.z;
  }
  return r;
}

TEST(Colour, TablesAreTheCieValues) {
  // Spot values of the CIE 1931 table (CIE 015:2018) and D65 (100 at 560 nm by definition).
  EXPECT_DOUBLE_EQ(cie::kXBar[0], 0.001368);
  EXPECT_DOUBLE_EQ(cie::kYBar[(555 - 380) / 5], 1.0);
  EXPECT_DOUBLE_EQ(cie::kZBar[(445 - 380) / 5], 1.7826);
  EXPECT_DOUBLE_EQ(cie::kD65[(560 - 380) / 5], 100.0);
  EXPECT_DOUBLE_EQ(cie::kD65[0], 49.9755);
}

TEST(Colour, EqualEnergyWhiteIsAtOneThird) {
  // The CIE functions are normalised to equal areas, so x = y = 1/3 up to the table's 7
  // significant digits and the truncation at 380/780 nm (the published sums agree to 1e-5).
  const Chromaticity c = chromaticity(integrate([](double) { return 1.0; }));
  EXPECT_NEAR(c.x, 1.0 / 3.0, 2e-5);
  EXPECT_NEAR(c.y, 1.0 / 3.0, 2e-5);
}

TEST(Colour, D65ChromaticityIsTheStandardWhitePoint) {
  // CIE 015:2018 defines colorimetry by summation over the 5 nm tables and gives D65 at
  // x = 0.31272, y = 0.32903 (2-degree observer): checks the tables to their 5 digits.
  Xyz sum;
  for (std::size_t i = 0; i < cie::kTableSize; ++i) {
    sum.x += cie::kD65[i] * cie::kXBar[i];
    sum.y += cie::kD65[i] * cie::kYBar[i];
    sum.z += cie::kD65[i] * cie::kZBar[i];
  }
  const Chromaticity s = chromaticity(sum);
  EXPECT_NEAR(s.x, 0.31272, 5e-6);
  EXPECT_NEAR(s.y, 0.32903, 5e-6);
  // The renderer integrates the linear interpolants instead (its wavelengths are continuous);
  // that moves the result by O(h^2 f'') with h = 5 nm (4e-5 here). Against IEC 61966-2-1's
  // (0.3127, 0.3290), rounded to 4 decimals (+-5e-5), the tolerance is the sum of both, 1e-4.
  const Chromaticity c = chromaticity(integrate([](double l) { return cie_d65(l); }));
  EXPECT_NEAR(c.x, 0.3127, 1e-4);
  EXPECT_NEAR(c.y, 0.3290, 1e-4);
}

TEST(Colour, UnitD65HasLuminanceOneAndIsSrgbWhite) {
  const Xyz w = integrate([](double l) { return illuminant_d65(l); });
  EXPECT_NEAR(w.y, 1.0, 1e-6);  // quadrature error only
  const LinearSrgb rgb = xyz_to_linear_srgb(w);
  // The IEC matrix is published to 4 decimals; its image of the tabulated D65 differs from
  // (1, 1, 1) by the rounding, 6e-4 at most: well inside 1/255.
  EXPECT_NEAR(rgb.r, 1.0, 1e-3);
  EXPECT_NEAR(rgb.g, 1.0, 1e-3);
  EXPECT_NEAR(rgb.b, 1.0, 1e-3);
}

TEST(Colour, SrgbMatricesAreInverse) {
  const LinearSrgb in{0.2, 0.5, 0.9};
  const LinearSrgb out = xyz_to_linear_srgb(linear_srgb_to_xyz(in));
  // Both 4-decimal matrices: their product is identity to ~5e-4 per entry.
  EXPECT_NEAR(out.r, in.r, 1e-3);
  EXPECT_NEAR(out.g, in.g, 1e-3);
  EXPECT_NEAR(out.b, in.b, 1e-3);
}

TEST(Colour, OutsideTheRangeIsBlack) {
  EXPECT_EQ(cie_xyz_bar(379.9).y, 0.0);
  EXPECT_EQ(cie_xyz_bar(780.1).x, 0.0);
  EXPECT_EQ(cie_d65(200.0), 0.0);
}

}  // namespace
}  // namespace thaw::render
