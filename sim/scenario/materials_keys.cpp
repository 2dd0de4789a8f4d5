#include "sim/scenario/materials_keys.h"

#include <array>

namespace thaw::sim {
namespace {

using M = Materials;
using Number = NumberKey<M>;

constexpr std::array<std::string_view, 2> kDensityModels{"water", "linear"};

// Ranges: within the span of real solids and liquids; typical: what the shipped scenarios and the
// literature use. Defaults: data/materials/ice_water.toml (its sources are cited there).
const MaterialsKey kMaterialsKeys[] = {
    {"ice_conductivity_w_mk",
     "Ice conductivity",
     "W/(m K)",
     "2.22",
     "k_ice [W/(m K)], 1e-3 .. 1e4: aerogel to diamond",
     Number{&M::ice_conductivity_w_mk},
     {1e-3, 1e4, 0.1, 10, true, "aerogel to diamond"}},
    {"ice_density_kg_m3",
     "Ice density",
     "kg/m^3",
     "917",
     "rho_ice [kg/m^3], 1 .. 1e5: real solids and liquids",
     Number{&M::ice_density_kg_m3},
     {1, 1e5, 500, 2000, true, "real solids and liquids"}},
    {"ice_specific_heat_j_kgk",
     "Ice specific heat",
     "J/(kg K)",
     "2050",
     "c_ice [J/(kg K)], 10 .. 1e5: real solids and liquids",
     Number{&M::ice_specific_heat_j_kgk},
     {10, 1e5, 500, 5000, true, "real solids and liquids"}},
    {"water_conductivity_w_mk",
     "Water conductivity",
     "W/(m K)",
     "0.56",
     "k_water [W/(m K)], 1e-3 .. 1e4: aerogel to diamond",
     Number{&M::water_conductivity_w_mk},
     {1e-3, 1e4, 0.1, 10, true, "aerogel to diamond"}},
    {"water_density_kg_m3",
     "Water density",
     "kg/m^3",
     "1000",
     "rho_water [kg/m^3], 1 .. 1e5: real solids and liquids",
     Number{&M::water_density_kg_m3},
     {1, 1e5, 500, 2000, true, "real solids and liquids"}},
    {"water_specific_heat_j_kgk",
     "Water specific heat",
     "J/(kg K)",
     "4186",
     "c_water [J/(kg K)], 10 .. 1e5: real solids and liquids",
     Number{&M::water_specific_heat_j_kgk},
     {10, 1e5, 500, 5000, true, "real solids and liquids"}},
    {"latent_heat_j_kg",
     "Latent heat",
     "J/kg",
     "333400",
     "latent heat of fusion L [J/kg], 100 .. 1e7: real solids",
     Number{&M::latent_heat_j_kg},
     {100, 1e7, 1e4, 1e6, true, "real solids"}},
    {"melting_point_c",
     "Melting point",
     "C",
     "0",
     "T_m [C], -273.15 .. 100: below the boiling point of water",
     Number{&M::melting_point_c},
     {-273.15, 100, -10, 10, false, "below the boiling point of water"}},
    {"water_density_model",
     "Water density model",
     "",
     "`water`",
     "buoyancy of the flowing water: `water` (density curve with its maximum at 4.03 C) or "
     "`linear` (`rho_water (1 - beta (T - T_m))`, for benchmark fluids)",
     ChoiceKey<M>{
         kDensityModels,
         [](const M& m) { return kDensityModels[static_cast<std::size_t>(m.water_density_model)]; },
         [](M& m, std::string_view name) {
           return set_enum_by_name(m.water_density_model, kDensityModels, name);
         }},
     {.flow = true}},
    {"water_expansion_per_k",
     "Water expansion",
     "1/K",
     "required with `linear`",
     "beta > 0 [1/K]; rejected with `water`",
     Number{&M::water_expansion_per_k},
     {.flow = true}},
    {"water_viscosity_pa_s",
     "Water viscosity",
     "Pa s",
     "water's table (CRC Handbook, 0-40 C)",
     "a constant dynamic viscosity > 0 [Pa s]",
     Number{&M::water_viscosity_pa_s},
     {.flow = true}},
};

}  // namespace

std::span<const MaterialsKey> materials_keys() {
  return kMaterialsKeys;
}

}  // namespace thaw::sim
