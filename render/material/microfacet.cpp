#include "render/material/microfacet.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/material/fresnel.h"

namespace thaw::render::microfacet {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float sqr(float x) {
  return x * x;
}

/// The generalised half vector of a refraction pair (Walter 2007, eq. 16), turned to +z; false
/// when the pair cannot come from one microfacet (a back-facing normal).
bool transmission_half_vector(const Vec3& wo, const Vec3& wi, float eta, Vec3& m) {
  m = wo + wi * eta;
  const float len2 = dot(m, m);
  if (!(len2 > 0.0f)) return false;
  m = m / std::sqrt(len2);
  if (m.z < 0.0f) m = -m;
  return dot(m, wo) > 0.0f && dot(m, wi) < 0.0f;
}

/// Node k of AlbedoTable: mu = (k / (N - 1))^2, denser towards grazing where E changes fastest,
/// and never exactly 0.
float node_mu(int k) {
  const float s = float(k) / float(AlbedoTable::kNodes - 1);
  return std::max(s * s, 1e-4f);
}

}  // namespace

float alpha_from_roughness(float roughness) {
  return std::max(roughness * roughness, 1e-4f);
}

float ggx_d(const Vec3& m, float alpha) {
  if (m.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  // D = alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2) (Walter 2007, eq. 33, rewritten without tan),
  // with sin^2 from m.x, m.y: 1 - cos^2 cancels catastrophically near the normal, where a smooth
  // surface's D lives (1 % error at roughness 0.05 in single precision).
  const float sin2 = m.x * m.x + m.y * m.y;
  return a2 / (kPi * sqr(a2 * m.z * m.z + sin2));
}

float ggx_lambda(const Vec3& w, float alpha) {
  const float z2 = w.z * w.z;
  if (z2 == 0.0f) return INFINITY;
  const float a2_tan2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
  return 0.5f * (std::sqrt(1.0f + a2_tan2) - 1.0f);
}

float ggx_g1(const Vec3& w, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(w, alpha));
}

float ggx_g2(const Vec3& wo, const Vec3& wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

Vec3 sample_visible_normal(const Vec3& wo, float alpha, float u1, float u2) {
  // Heitz 2018, listing 1: stretch to the hemisphere configuration, sample the projected disk
  // (warped towards the visible half), unstretch.
  const Vec3 vh = normalize(Vec3{alpha * wo.x, alpha * wo.y, wo.z});
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = lensq > 0.0f ? Vec3{-vh.y, vh.x, 0.0f} / std::sqrt(lensq) : Vec3{1, 0, 0};
  const Vec3 t2 = cross(vh, t1);
  const float r = std::sqrt(u1);
  const float phi = 2.0f * kPi * u2;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)});
}

float visible_normal_pdf(const Vec3& wo, const Vec3& m, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return ggx_g1(wo, alpha) * std::max(0.0f, dot(wo, m)) * ggx_d(m, alpha) / wo.z;
}

float fresnel(float cos_i, float eta) {
  return fresnel_dielectric(cos_i, eta);
}

bool refract_about(const Vec3& wo, const Vec3& m, float eta, Vec3& wi) {
  const float cos_i = dot(wo, m);
  const float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  wi = -wo / eta + m * (cos_i / eta - cos_t);
  return true;
}

float dielectric_eval(const Vec3& wo, const Vec3& wi, float alpha, float eta) {
  if (wo.z <= 0.0f || wi.z == 0.0f) return 0.0f;
  if (wi.z > 0.0f) {
    const Vec3 m = normalize(wo + wi);
    return ggx_d(m, alpha) * ggx_g2(wo, wi, alpha) * fresnel(dot(wo, m), eta) /
           (4.0f * wo.z * wi.z);
  }
  Vec3 m;
  if (!transmission_half_vector(wo, wi, eta, m)) return 0.0f;
  const float om = dot(wo, m), im = dot(wi, m);
  // Walter 2007, eq. 21, without the 1 / eta^2 of radiance (basic radiance, see the header).
  const float denom = sqr(im + om / eta);
  return ggx_d(m, alpha) * ggx_g2(wo, wi, alpha) * (1.0f - fresnel(om, eta)) *
         std::abs(im * om / (wi.z * wo.z * denom));
}

float dielectric_pdf(const Vec3& wo, const Vec3& wi, float alpha, float eta) {
  if (wo.z <= 0.0f || wi.z == 0.0f) return 0.0f;
  if (wi.z > 0.0f) {
    const Vec3 m = normalize(wo + wi);
    const float om = dot(wo, m);
    if (om <= 0.0f) return 0.0f;
    // Reflection's Jacobian dm/dwi = 1 / (4 |wi.m|) (Walter 2007, eq. 14).
    return visible_normal_pdf(wo, m, alpha) / (4.0f * om) * fresnel(om, eta);
  }
  Vec3 m;
  if (!transmission_half_vector(wo, wi, eta, m)) return 0.0f;
  const float om = dot(wo, m), im = dot(wi, m);
  // Refraction's Jacobian dm/dwi = |wi.m| / (wi.m + wo.m / eta)^2 (Walter 2007, eq. 17, in the
  // units of eta used here).
  return visible_normal_pdf(wo, m, alpha) * std::abs(im) / sqr(im + om / eta) *
         (1.0f - fresnel(om, eta));
}

DielectricSplit dielectric_split(const Vec3& wo, const Vec3& m, float alpha, float eta) {
  DielectricSplit s;
  const float c = dot(wo, m);
  if (c <= 0.0f) return s;
  const float g1 = ggx_g1(wo, alpha);
  s.fresnel = fresnel(c, eta);
  s.wr = m * (2.0f * c) - wo;
  if (s.wr.z > 0.0f) s.weight_r = s.fresnel * ggx_g2(wo, s.wr, alpha) / g1;
  if (s.fresnel < 1.0f && refract_about(wo, m, eta, s.wt) && s.wt.z < 0.0f)
    s.weight_t = (1.0f - s.fresnel) * ggx_g2(wo, s.wt, alpha) / g1;
  return s;
}

bool dielectric_sample(const Vec3& wo, float alpha, float eta, float u1, float u2, float uc,
                       DielectricSample& out) {
  if (wo.z <= 0.0f) return false;
  const Vec3 m = sample_visible_normal(wo, alpha, u1, u2);
  const float c = dot(wo, m);
  if (c <= 0.0f) return false;
  const float f = fresnel(c, eta);
  const float pdf_m = visible_normal_pdf(wo, m, alpha);
  if (uc < f) {
    out.wi = m * (2.0f * c) - wo;
    if (out.wi.z <= 0.0f) return false;
    out.transmitted = false;
    out.pdf = pdf_m / (4.0f * c) * f;
  } else {
    if (!refract_about(wo, m, eta, out.wi) || out.wi.z >= 0.0f) return false;
    out.transmitted = true;
    const float im = dot(out.wi, m);
    out.pdf = pdf_m * std::abs(im) / sqr(im + c / eta) * (1.0f - f);
  }
  out.weight = ggx_g2(wo, out.wi, alpha) / ggx_g1(wo, alpha);
  return true;
}

float conductor_eval(const Vec3& wo, const Vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const Vec3 m = normalize(wo + wi);
  return ggx_d(m, alpha) * ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z);
}

float conductor_pdf(const Vec3& wo, const Vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const Vec3 m = normalize(wo + wi);
  const float om = dot(wo, m);
  return om > 0.0f ? visible_normal_pdf(wo, m, alpha) / (4.0f * om) : 0.0f;
}

bool conductor_sample(const Vec3& wo, float alpha, float u1, float u2, Vec3& wi, float& weight) {
  if (wo.z <= 0.0f) return false;
  const Vec3 m = sample_visible_normal(wo, alpha, u1, u2);
  const float c = dot(wo, m);
  if (c <= 0.0f) return false;
  wi = m * (2.0f * c) - wo;
  if (wi.z <= 0.0f) return false;
  weight = ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha);
  return true;
}

AlbedoTable::AlbedoTable(float alpha, float eta) : m_alpha(alpha) {
  for (int k = 0; k < kNodes; ++k) {
    const float mu = node_mu(k);
    const Vec3 wo{std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu};
    double sum = 0.0;
    for (int i = 0; i < kQuadrature; ++i) {
      for (int j = 0; j < kQuadrature; ++j) {
        const float u1 = (float(i) + 0.5f) / kQuadrature, u2 = (float(j) + 0.5f) / kQuadrature;
        const Vec3 m = sample_visible_normal(wo, alpha, u1, u2);
        if (eta > 0.0f) {
          const DielectricSplit s = dielectric_split(wo, m, alpha, eta);
          sum += double(s.weight_r) + double(s.weight_t);
        } else {
          const float c = dot(wo, m);
          const Vec3 wi = m * (2.0f * c) - wo;
          if (c > 0.0f && wi.z > 0.0f) sum += ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha);
        }
      }
    }
    // Never 0: a lobe that loses everything at grazing is not brightened without bound.
    m_e[std::size_t(k)] = std::max(0.05f, float(sum / double(kQuadrature * kQuadrature)));
  }
}

float AlbedoTable::albedo(float mu) const {
  const float s = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(kNodes - 1);
  const int k = std::min(int(s), kNodes - 2);
  const float t = s - float(k);
  return m_e[std::size_t(k)] * (1.0f - t) + m_e[std::size_t(k) + 1] * t;
}

Frame::Frame(const Vec3& normal) : n(normal) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  s = Vec3{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t = Vec3{b, sign + n.y * n.y * a, -n.y};
}

}  // namespace thaw::render::microfacet
