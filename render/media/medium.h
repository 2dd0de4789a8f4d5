#pragma once
// An optical medium as the integrator sees it: a name, n(lambda) and Beer-Lambert absorption.
// Parsing and building are separate (STYLE 6): parse_medium_spec() (medium_parser.h, the file
// layer) turns a [media.NAME] TOML table into a plain MediumSpec, resolve_preset()
// (medium_library.h) fills in a preset from the built-in library (data/optics/media.toml), and
// build_medium() (here, render's core) validates over 380-780 nm, never seeing TOML.
//
// [media.NAME] keys (exactly one index source):
//   preset = "water-0c"                     a library entry (`thaw materials` lists them)
//   ior = 1.31                              constant index (not dispersive)
//   sellmeier = { B = [...], C = [...] }    C in um^2; optional form = "n-1" for gases
//   cauchy = { A = 1.2995, B = 0.0038, C = 0.0 }       lambda in um
//   table = { wavelength_nm = [...], n = [...] }       must cover 380-780 nm
//   iapws97 = { temperature_c = 0.0, density_kg_m3 = 999.84 }
// plus optional absorption_per_m = 0.5 or { wavelength_nm = [...], per_m = [...] } [1/m]
// (replaces a preset's) and absorption_scale = 10.0 (multiplies it; artistic tinting).
// Scattering (cloudy ice; render/media/scattering.h): scattering_per_m = 30.0 [1/m] with
// asymmetry = 0.86 (Henyey-Greenstein g), or bubbles = { air_fraction = 1e-3, radius_m = 5e-5 }.
#include <optional>
#include <string>

#include "render/media/absorption.h"
#include "render/media/ior_model.h"

namespace thaw::render::media {

/// A medium as written in a scene or the library, before presets are resolved.
struct MediumSpec {
  std::string name;    ///< "ice"
  std::string file;    ///< source file, for error messages
  std::string key;     ///< key path, for error messages: "media.ice"
  std::string preset;  ///< library entry name, or empty
  std::optional<IorModel> ior;
  std::optional<Absorption> absorption;  ///< unscaled
  std::optional<double> absorption_scale;
  /// scattering coefficient [1/m] and Henyey-Greenstein asymmetry, as given or from bubbles
  /// (render/media/scattering.h); unset: a clear medium
  std::optional<double> scattering_per_m, asymmetry;
  // Library documentation (empty in scenes).
  std::string description, source, absorption_source;
};

class Medium {
 public:
  Medium(std::string name, IorModel ior, Absorption absorption, std::string source = {});

  const std::string& name() const { return m_name; }
  const IorModel& ior_model() const { return m_ior; }
  const Absorption& absorption() const { return m_absorption; }
  const std::string& source() const { return m_source; }

  /// Whether refraction into or out of this medium separates wavelengths.
  bool is_dispersive() const { return m_ior.is_dispersive(); }
  double n_at(double lambda_nm) const { return m_ior.n_at(lambda_nm); }
  SampledSpectrum n(const SampledWavelengths& w) const { return m_ior.n(w); }
  /// Absorption coefficient [1/m], absorption_scale included.
  double absorption_per_m_at(double lambda_nm) const { return m_absorption.per_m_at(lambda_nm); }
  bool absorbs() const { return !m_absorption.is_zero(); }
  /// Scattering coefficient [1/m] (grey: bubbles far larger than the wavelength) and the
  /// Henyey-Greenstein asymmetry g of its phase function; 0 = a clear medium.
  double scattering_per_m() const { return m_scattering_per_m; }
  double asymmetry() const { return m_asymmetry; }
  bool scatters() const { return m_scattering_per_m > 0.0; }
  void set_scattering(double per_m, double asymmetry) {
    m_scattering_per_m = per_m;
    m_asymmetry = asymmetry;
  }
  /// Beer-Lambert transmittance of a segment of `distance_m` metres inside this medium.
  SampledSpectrum transmittance(double distance_m, const SampledWavelengths& w) const {
    return m_absorption.transmittance(distance_m, w);
  }

 private:
  std::string m_name;
  IorModel m_ior;
  Absorption m_absorption;
  std::string m_source;
  double m_scattering_per_m = 0.0, m_asymmetry = 0.0;
};

/// Validates the index and absorption over 380-780 nm (errors name the medium and key) and builds
/// the medium. A preset must have been resolved first (resolve_preset, medium_library.h).
Medium build_medium(const MediumSpec& spec);

}  // namespace thaw::render::media
