#include "render/scene/caustic_keys.h"

#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

using C = CausticSettings;

const CausticKey kCausticKeys[] = {
    {"enabled", "Caustics", "", "true",
     "light through dielectrics onto diffuse surfaces by photon tracing (section \"Caustics\"); "
     "false = the Whitted way (dielectrics cast full shadows), set in the POV-Ray comparison "
     "scenes `s1*`, `s3*`, `s4*`",
     FlagKey<C>{&C::enabled}},
    {"photons", "Caustic photons", "", "automatic (150000)",
     "photons aimed at the dielectrics, all lights together; an integer 1..1e7 (`1e6` is "
     "accepted); memory grows with the count, about 200 bytes per photon (1e7 photons: 2.1 GB "
     "peak)",
     OptionalIntegerKey<C>{&C::photons, caustic_photons_problem}},
    {"radius", "Caustic radius", "", "automatic",
     "radius of the density estimate [scene units], 1e-12..1e12; automatic: R sqrt(64 / N_k), the "
     "smallest over the cones (section \"Caustics\")",
     OptionalNumberKey<C>{&C::radius, caustic_radius_problem}},
};

}  // namespace

std::span<const CausticKey> caustic_keys() {
  return kCausticKeys;
}

}  // namespace thaw::render
