#pragma once
// Index of refraction of a medium as a function of wavelength. Only the constant model exists
// now; issue 5 adds Sellmeier, Cauchy and tabulated models behind the same interface, and
// `is_dispersive()` lets the integrator keep non-dispersive scenes on the cheap path.
#include <string>

namespace thaw::render {

class IorModel {
 public:
  enum class Kind { constant };

  IorModel() = default;
  /// A wavelength-independent index n (> 0).
  static IorModel constant(double n) {
    IorModel m;
    m.m_n = n;
    return m;
  }

  Kind kind() const { return m_kind; }
  /// n at `wavelength_nm` [nm].
  double at(double /*wavelength_nm*/) const { return m_n; }
  /// n at the helium d line (587.56 nm), the value an RGB renderer uses.
  double n_d() const { return m_n; }
  bool is_dispersive() const { return false; }

 private:
  Kind m_kind = Kind::constant;
  double m_n = 1.0;
};

}  // namespace thaw::render
