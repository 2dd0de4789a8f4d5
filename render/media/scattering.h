#pragma once
// Scattering inside a dielectric medium: cloudy ice. Freezer ice holds air that came out of
// solution as the water froze, trapped as bubbles far larger than the wavelength (tens of um), so
// geometric optics applies: each bubble removes twice its cross-section from a beam (extinction
// efficiency Q_ext = 2, half of it diffraction; van de Hulst 1957, ch. 8), and a volume fraction f
// of bubbles of radius r, n = f / (4/3 pi r^3) per m^3, scatters with
//   sigma_s = n Q_ext pi r^2 = 1.5 f / r   [1/m]
// (f = 1e-3, r = 50 um: 30 /m, a mean free path of 3.3 cm), grey across the visible, and with a
// strongly forward phase whose asymmetry for an air bubble in ice is about g = 0.86 (geometric
// optics with diffraction; Mullen and Warren 1988, "Theory of the optical properties of lake
// ice", J. Geophys. Res. 93(D7), 8403). Absorption stays the medium's own (Beer-Lambert). The
// phase function is Henyey-Greenstein's with that g. Knows nothing about TOML or rays.
#include <optional>
#include <string>

namespace thaw::render::media {

/// g of an air bubble in ice (Mullen and Warren 1988; see above).
inline constexpr double kBubbleAsymmetry = 0.86;
/// Largest accepted scattering coefficient [1/m] (a mean free path of 1 um: milk is ~1e4 /m).
inline constexpr double kMaxScatteringPerM = 1e6;

/// sigma_s = 1.5 f / r [1/m] of bubbles of volume fraction f and radius r [m].
double bubble_scattering_per_m(double air_fraction, double radius_m);

/// scattering_per_m: finite, in [0, kMaxScatteringPerM].
std::optional<std::string> scattering_problem(double per_m);
/// asymmetry: in (-1, 1) (|g| = 1 is a delta, not a phase function).
std::optional<std::string> asymmetry_problem(double g);
/// bubbles.air_fraction: in [0, 1) (1 or more is no longer ice with bubbles).
std::optional<std::string> air_fraction_problem(double f);
/// bubbles.radius_m: finite and in (0, 0.01] m (beyond a centimetre a bubble is a cavity: model
/// it as an interface).
std::optional<std::string> bubble_radius_problem(double radius_m);

}  // namespace thaw::render::media
