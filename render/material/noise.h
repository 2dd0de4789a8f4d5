#pragma once
// Procedural solid noise for textures, each filtered over a footprint of width w [the noise's
// own units] (the ray cone's, render/material/texture.h), so that detail finer than a pixel fades
// to its mean instead of aliasing:
// - perlin(p): Perlin's improved gradient noise (Perlin 2002, "Improving noise", SIGGRAPH;
//   quintic fade, 12 edge gradients), in about [-1, 1], mean 0, one feature per unit;
// - fbm(p, w, octaves): a sum of octaves 2^-o perlin(2^o p), each faded out as its period meets
//   the footprint (frequency clamping, Norton, Rockwood & Skolmoski 1982: an octave whose
//   frequency f has f w >= 1/2 is replaced by its mean 0, smoothly from f w = 1/4);
// - worley(p, w): Worley's cellular noise (Worley 1996, "A cellular texture basis function"),
//   F1, the distance to the nearest of one feature point per unit cell, in [0, ~1]; faded to its
//   mean (kWorleyMean) as the cells meet the footprint;
// - wood(p, w): flat-sawn planks: growth rings around an axis under each board, perturbed by
//   fbm, with a fine grain along the board; planks along x, one unit wide in z, a thin dark
//   joint between them; a value in [0, 1] (0 early wood, 1 late wood / joint).
// Deterministic (fixed permutation), thread-safe, no state. Knows nothing about rays or colour.
#include "render/math/vec3.h"

namespace thaw::render::noise {

/// Perlin's improved noise at p, in about [-1, 1].
float perlin(const Vec3& p);

/// Octaves of perlin(), filtered to footprint width w.
float fbm(const Vec3& p, float w, int octaves);

/// The mean of worley() over many cells.
inline constexpr float kWorleyMean = 0.55f;

/// Worley F1 at p (one feature point per unit cell), filtered to footprint width w.
float worley(const Vec3& p, float w);

/// Flat-sawn wood planks at p (planks one unit wide), filtered to footprint width w; in [0, 1].
float wood(const Vec3& p, float w);

/// Slate: mottled fbm over Worley cleavage patches, filtered to footprint width w; in [0, 1].
float slate(const Vec3& p, float w);

}  // namespace thaw::render::noise
