#pragma once
// Opaque surface materials of the Whitted integrator (dielectric interfaces are not materials:
// they are surfaces between two media, see render/scene/scene.h).
//   matte    Lambert: ambient + sum over lights of albedo * light * max(0, n.l)
//   metal    tinted perfect mirror: colour * reflected radiance
//   phong    the classic model (ka, kd, ks, shininess, reflectance, transmittance, ior)
//   emissive a visible light surface: emission, no shading
#include <memory>

#include "render/material/microfacet.h"
#include "render/material/texture.h"

namespace thaw::render {

struct Material {
  enum class Kind { matte, metal, phong, emissive };
  Kind kind = Kind::matte;
  /// albedo (matte, phong) or mirror tint (metal)
  Texture texture;
  // Phong terms (matte is ka = kd = 1, the rest 0).
  float ka = 1.0f, kd = 1.0f, ks = 0.0f, shininess = 32.0f;
  float reflectance = 0.0f, transmittance = 0.0f;
  /// index of refraction behind a phong surface relative to the medium in front
  float ior = 1.0f;
  /// emitted radiance (emissive), linear RGB
  Rgb emission{0, 0, 0};
  /// metal and phong mirror terms: GGX alpha (0 = perfect mirror) and the directional albedo of
  /// the F = 1 lobe for the multiple-scattering compensation (render/material/microfacet.h)
  float alpha = 0.0f;
  std::shared_ptr<const microfacet::AlbedoTable> albedo;
};

}  // namespace thaw::render
