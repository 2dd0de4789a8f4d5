#pragma once
// Published mean Nusselt numbers of the differentially heated square cavity (Pr 0.71) and the
// two-grid arithmetic the cavity tests share.
#include <cmath>

namespace thaw::sim::flow::test {

/// de Vahl Davis (1983), Int. J. Numer. Methods Fluids 3:249, Table: mean Nu.
inline constexpr double kDeVahlDavisNu1e4 = 2.243, kDeVahlDavisNu1e5 = 4.519,
                        kDeVahlDavisNu1e6 = 8.800;
/// Hortmann, Peric & Scheuerer (1990), Int. J. Numer. Methods Fluids 11:189: finite volumes with
/// multigrid to 640 x 640 cells, Richardson-extrapolated; mean Nu.
inline constexpr double kHortmannNu1e4 = 2.24475, kHortmannNu1e5 = 4.52164,
                        kHortmannNu1e6 = 8.82513;

struct CavityCheck {
  double extrapolated = 0;        // Richardson with the formal order 2
  double extrapolated_error = 0;  // relative to the reference
  double order = 0;               // log2(error coarse / error fine) against the reference
};

/// Grids h and h/2 giving nu_coarse and nu_fine.
inline CavityCheck check_two_grids(double nu_coarse, double nu_fine, double reference) {
  CavityCheck c;
  c.extrapolated = nu_fine + (nu_fine - nu_coarse) / 3.0;
  c.extrapolated_error = (c.extrapolated - reference) / reference;
  c.order = std::log2(std::abs(nu_coarse - reference) / std::abs(nu_fine - reference));
  return c;
}

/// Observed order from three grids h, h/2, h/4 without a reference.
inline double observed_order(double n1, double n2, double n4) {
  return std::log2(std::abs(n1 - n2) / std::abs(n2 - n4));
}

}  // namespace thaw::sim::flow::test
