#pragma once
// Rough surfaces: the GGX (Trowbridge-Reitz) microfacet model of Walter, Marschner, Li and
// Torrance, "Microfacet Models for Refraction through Rough Surfaces" (EGSR 2007), with Heitz's
// height-correlated masking-shadowing ("Understanding the Masking-Shadowing Function", JCGT 2014,
// eq. 99) and sampling of the visible normals ("Sampling the GGX Distribution of Visible
// Normals", JCGT 2018). Evaluation, sampling and pdf side by side (pbrt-v4 DielectricBxDF with
// TrowbridgeReitzDistribution), all in a local frame whose +z is the macro-surface normal on the
// side of wo (the direction towards the viewer). Knows nothing about scenes, media or spectra.
//
// Units: the dielectric BSDF is written for *basic radiance* L / n^2, the quantity the Whitted
// integrators carry (their smooth interfaces weigh the transmitted ray by 1 - R, no n^2): its
// transmission lobe is pbrt-v4's "importance" form, and the sampling weight of either lobe is
// F G2 / G1 (reflection) or (1 - F) G2 / G1 (transmission) with the visible normal m. Generalised
// reciprocity in these units reads f(wo, wi) / n_i^2 = f(wi, wo) / n_o^2 (tested).
//
// Energy lost to single scattering (rays that would scatter again among the microfacets, G2 < G1)
// is put back by the compensation of Turquin, "Practical multiple scattering compensation for
// microfacet models" (Tech. report, Weta Digital 2019): the lobe is divided by its directional
// albedo E(mu_o), tabulated in code per roughness and relative index (AlbedoTable). Conductors
// use his tinted form 1 + F0 (1 - E) / E. The compensated lobe passes the white furnace exactly
// (to the table's interpolation error); its compensation factor depends on mu_o only, so it is
// reciprocal only to O(1 - E) (the single-scattering part is exactly reciprocal).
#include <array>
#include <vector>

#include "render/math/vec3.h"

namespace thaw::render::microfacet {

/// GGX alpha from the perceptual roughness in [0, 1] of scene files (alpha = roughness^2, as
/// Burley 2012), kept >= 1e-4 so that the distribution stays representable in single precision.
float alpha_from_roughness(float roughness);

/// Normal distribution D(m) [1/sr] for a local unit m (m.z = cos theta_m).
float ggx_d(const Vec3& m, float alpha);
/// Smith's Lambda(w) for GGX (Heitz 2014, eq. 72).
float ggx_lambda(const Vec3& w, float alpha);
/// Masking G1(w) = 1 / (1 + Lambda(w)).
float ggx_g1(const Vec3& w, float alpha);
/// Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)).
float ggx_g2(const Vec3& wo, const Vec3& wi, float alpha);

/// A visible normal for wo (wo.z > 0) from two uniform numbers in [0, 1) (Heitz 2018, listing 1).
Vec3 sample_visible_normal(const Vec3& wo, float alpha, float u1, float u2);
/// Its density over m: D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z.
float visible_normal_pdf(const Vec3& wo, const Vec3& m, float alpha);

/// Smooth-interface Fresnel reflectance at cos(theta) = `cos_i` on the incident side, relative
/// index eta = n_transmitted / n_incident (render/material/fresnel.h).
float fresnel(float cos_i, float eta);

/// Refracts wo (pointing away from the surface, on m's side) through microfacet m; eta as
/// above. False under total internal reflection.
bool refract_about(const Vec3& wo, const Vec3& m, float eta, Vec3& wi);

/// Rough dielectric: eta = n on the far side / n on wo's side, wo.z > 0.
/// f(wo, wi) [1/sr], basic-radiance form: reflection for wi.z > 0, transmission for wi.z < 0.
float dielectric_eval(const Vec3& wo, const Vec3& wi, float alpha, float eta);
/// Density of dielectric_sample's direction over the sphere [1/sr]: a visible normal, then
/// reflection with probability F(wo.m), else refraction.
float dielectric_pdf(const Vec3& wo, const Vec3& wi, float alpha, float eta);

struct DielectricSample {
  Vec3 wi;
  /// f |wi.z| / pdf (F, 1 - F and the pdf's choice cancel: G2 / G1)
  float weight = 0;
  float pdf = 0;
  bool transmitted = false;
};
/// One direction (u1, u2: the visible normal; uc: reflect or refract). False when the sample is
/// lost (the direction leaves on the wrong side of the macro surface).
bool dielectric_sample(const Vec3& wo, float alpha, float eta, float u1, float u2, float uc,
                       DielectricSample& out);

/// Both branches of one visible normal m, for integrators that follow both (the Whitted tree):
/// reflection wr with weight F G2(wo, wr) / G1(wo); refraction wt with (1 - F) G2(wo, wt) / G1(wo)
/// (weights are 0 for a branch that does not exist or leaves on the wrong side).
struct DielectricSplit {
  Vec3 wr, wt;
  float fresnel = 1, weight_r = 0, weight_t = 0;
};
DielectricSplit dielectric_split(const Vec3& wo, const Vec3& m, float alpha, float eta);

/// Rough mirror with F = 1 (conductor tints and Fresnel are applied by the caller):
/// f = D G2 / (4 wo.z wi.z).
float conductor_eval(const Vec3& wo, const Vec3& wi, float alpha);
float conductor_pdf(const Vec3& wo, const Vec3& wi, float alpha);
/// Reflection about a visible normal; weight = G2 / G1. False when wi.z <= 0.
bool conductor_sample(const Vec3& wo, float alpha, float u1, float u2, Vec3& wi, float& weight);

/// Directional albedo E(mu_o) = int f |cos_i| dwi of the single-scattering lobe (dielectric:
/// reflection + transmission at relative index eta; eta <= 0: the F = 1 conductor) for one
/// alpha, tabulated on kNodes values of mu_o = wo.z in (0, 1] by a deterministic product
/// quadrature over the visible normals (kQuadrature^2 midpoints of (u1, u2), so each node is
/// E = mean of the sampling weight, exact for the estimator used at render time), and
/// interpolated linearly. 64 x 64 quadrature points and 64 nodes: the furnace tests hold the
/// compensated lobe to 1 within 0.2 % down to roughness 0.05.
class AlbedoTable {
 public:
  static constexpr int kNodes = 64, kQuadrature = 64;
  AlbedoTable() = default;
  AlbedoTable(float alpha, float eta);
  /// E(mu) for mu in (0, 1]
  float albedo(float mu) const;
  /// The compensation 1 / E(mu) of the dielectric (Turquin 2019, sec. 4).
  float dielectric_compensation(float mu) const { return 1.0f / albedo(mu); }
  /// Turquin's conductor factor 1 + f0 (1 - E) / E for a reflectance f0 in [0, 1].
  float conductor_compensation(float mu, float f0) const {
    const float e = albedo(mu);
    return 1.0f + f0 * (1.0f - e) / e;
  }
  float alpha() const { return m_alpha; }

 private:
  float m_alpha = 0;
  std::array<float, kNodes> m_e{};
};

/// A local frame around unit normal n (Duff et al. 2017, "Building an orthonormal basis,
/// revisited").
struct Frame {
  Vec3 s, t, n;
  explicit Frame(const Vec3& normal);
  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace thaw::render::microfacet
