#include "render/material/noise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace thaw::render::noise {

namespace {

/// Perlin's permutation of 0..255, here drawn once by a fixed Fisher-Yates shuffle (any
/// permutation serves; a fixed one keeps every frame and run identical), repeated twice.
const std::array<std::uint8_t, 512>& permutation() {
  static const std::array<std::uint8_t, 512> table = [] {
    std::array<std::uint8_t, 512> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = std::uint8_t(i);
    std::uint32_t state = 0x9E3779B9u;
    for (int i = 255; i > 0; --i) {
      state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG
      const auto j = std::size_t((state >> 8) % std::uint32_t(i + 1));
      std::swap(t[std::size_t(i)], t[j]);
    }
    for (std::size_t i = 0; i < 256; ++i) t[i + 256] = t[i];
    return t;
  }();
  return table;
}

float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}
float lerp(float t, float a, float b) {
  return a + t * (b - a);
}
/// The dot product of one of Perlin's 12 edge gradients (chosen by the hash) with (x, y, z).
float grad(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

/// 1 where the footprint w resolves detail of frequency f (f w <= 1/4), 0 where it cannot
/// (f w >= 1/2), smooth in between.
float resolved(float f, float w) {
  const float x = std::clamp((f * w - 0.25f) / 0.25f, 0.0f, 1.0f);
  return 1.0f - x * x * (3.0f - 2.0f * x);
}

/// A hash of an integer cell to [0, 1) (Jenkins-style avalanche of the three coordinates).
float cell_hash(int x, int y, int z, std::uint32_t salt) {
  std::uint32_t h = std::uint32_t(x) * 0x8da6b343u ^ std::uint32_t(y) * 0xd8163841u ^
                    std::uint32_t(z) * 0xcb1ab31fu ^ salt;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

float perlin(const Vec3& p) {
  const auto& perm = permutation();
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int X = int(fx) & 255, Y = int(fy) & 255, Z = int(fz) & 255;
  const float x = p.x - fx, y = p.y - fy, z = p.z - fz;
  const float u = fade(x), v = fade(y), w = fade(z);
  const auto P = [&](int i) { return int(perm[std::size_t(i)]); };
  const int A = P(X) + Y, AA = P(A) + Z, AB = P(A + 1) + Z;
  const int B = P(X + 1) + Y, BA = P(B) + Z, BB = P(B + 1) + Z;
  return lerp(
      w,
      lerp(v, lerp(u, grad(P(AA), x, y, z), grad(P(BA), x - 1, y, z)),
           lerp(u, grad(P(AB), x, y - 1, z), grad(P(BB), x - 1, y - 1, z))),
      lerp(v, lerp(u, grad(P(AA + 1), x, y, z - 1), grad(P(BA + 1), x - 1, y, z - 1)),
           lerp(u, grad(P(AB + 1), x, y - 1, z - 1), grad(P(BB + 1), x - 1, y - 1, z - 1))));
}

float fbm(const Vec3& p, float w, int octaves) {
  float sum = 0.0f, amplitude = 0.5f, frequency = 1.0f;
  for (int o = 0; o < octaves; ++o) {
    const float keep = resolved(frequency, w);
    if (keep <= 0.0f) break;  // every finer octave is faded out too
    sum += keep * amplitude * perlin(p * frequency);
    amplitude *= 0.5f;
    frequency *= 2.0f;
  }
  return sum;
}

float worley(const Vec3& p, float w) {
  const float keep = resolved(1.0f, w);
  if (keep <= 0.0f) return kWorleyMean;
  const int cx = int(std::floor(p.x)), cy = int(std::floor(p.y)), cz = int(std::floor(p.z));
  float best = 1e30f;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = cx + dx, y = cy + dy, z = cz + dz;
        const Vec3 feature{float(x) + cell_hash(x, y, z, 1u), float(y) + cell_hash(x, y, z, 2u),
                           float(z) + cell_hash(x, y, z, 3u)};
        const Vec3 d = feature - p;
        best = std::min(best, dot(d, d));
      }
  return kWorleyMean + keep * (std::sqrt(best) - kWorleyMean);
}

float wood(const Vec3& p, float w) {
  // The board: planks along x, one unit wide in z.
  const float fz = std::floor(p.z);
  const int k = int(fz);
  const float z = p.z - fz;
  const float r1 = cell_hash(k, 0, 0, 11u), r2 = cell_hash(k, 0, 0, 12u),
              r3 = cell_hash(k, 0, 0, 13u);
  // The log's axis under the board (flat sawn): depth 0.4-1.6 board widths, off-centre, tilted.
  const float ya = -(0.4f + 1.2f * r1);
  const float za = 0.5f + (r2 - 0.5f) * 1.4f + 0.02f * (r3 - 0.5f) * p.x;
  const float dy = p.y - ya, dzz = z - za;
  const float r = std::sqrt(dy * dy + dzz * dzz);
  constexpr float kRingsPerUnit = 7.0f;
  const Vec3 q{p.x * 0.12f + 31.0f * float(k), p.y * 1.5f, p.z * 1.5f};
  const float v = r * kRingsPerUnit + 0.6f * fbm(q, w * 1.5f, 4);
  // Ring frequency across the surface: the rings' spacing seen on the board is the ring
  // spacing divided by the sine of the angle between the surface and the ring (flat-sawn
  // "cathedrals" where the board is tangent to a ring).
  const float along = std::max(std::abs(dzz) / std::max(r, 1e-6f), 0.15f);
  const float ring_keep = resolved(kRingsPerUnit * along, w);
  const float t = v - std::floor(v);
  const float ring = ring_keep * (t * t * t) + (1.0f - ring_keep) * 0.25f;  // mean of t^3
  // Fine grain along the board.
  const Vec3 g{p.x * 0.8f, p.y * 30.0f, p.z * 30.0f + 7.0f * float(k)};
  const float grain = fbm(g, w * 30.0f, 3);
  float value = 0.2f + 0.55f * ring + 0.2f * grain + 0.2f * (r3 - 0.5f);
  // The joint between boards: 0.006 units wide, averaged over the footprint.
  constexpr float kJoint = 0.006f;
  const float edge = std::min(z, 1.0f - z);
  const float joint_keep = resolved(0.5f / kJoint, w);
  const float joint =
      joint_keep * (1.0f - smoothstep(0.5f * kJoint, kJoint, edge)) + (1.0f - joint_keep) * kJoint;
  value += joint * (1.0f - value);
  return std::clamp(value, 0.0f, 1.0f);
}

float slate(const Vec3& p, float w) {
  const float mottle = fbm(p * 2.0f, w * 2.0f, 6);
  const float patches = worley(p * 0.7f, w * 0.7f) - kWorleyMean;
  const float fine = fbm(p * 24.0f + Vec3{5.0f, 3.0f, 1.0f}, w * 24.0f, 3);
  return std::clamp(0.5f + 0.45f * mottle + 0.35f * patches + 0.12f * fine, 0.0f, 1.0f);
}

}  // namespace thaw::render::noise
