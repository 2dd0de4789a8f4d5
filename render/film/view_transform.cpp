#include "render/film/view_transform.h"

#include <algorithm>
#include <cmath>

namespace thaw::render {

namespace {

// Wrensch 2023 (constants as published; each matrix row sums to 1 within 1e-4, so grey stays
// grey).
constexpr float kMinEv = -12.47393f, kMaxEv = 4.026069f;
constexpr float kInset[3][3] = {{0.842479062253094f, 0.0784335999999992f, 0.0792237451477643f},
                                {0.0423282422610123f, 0.878468636469772f, 0.0791661274605434f},
                                {0.0423756549057051f, 0.0784336f, 0.879142973793104f}};
constexpr float kOutset[3][3] = {{1.19687900512017f, -0.0980208811401368f, -0.0990297440797205f},
                                 {-0.0528968517574562f, 1.15190312990417f, -0.0989611768448433f},
                                 {-0.0529716355144438f, -0.0980434501171241f, 1.15107367264116f}};

Rgb apply(const float (&m)[3][3], const Rgb& c) {
  return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b,
          m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
          m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
}

/// log2 encoding and the sigmoid's polynomial: a linear value to a display value in ~[0, 1].
float curve(float linear) {
  const float ev = std::clamp(std::log2(std::max(linear, 1e-10f)), kMinEv, kMaxEv);
  const float x = (ev - kMinEv) / (kMaxEv - kMinEv);
  const float x2 = x * x, x4 = x2 * x2;
  return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 +
         0.1191f * x - 0.00232f;
}

float decode(float display) {
  return std::pow(std::clamp(display, 0.0f, 1.0f), 2.2f);
}

}  // namespace

Rgb agx_view(const Rgb& linear) {
  if (!(linear.r == linear.r) || !(linear.g == linear.g) || !(linear.b == linear.b))
    return {0.0f, 0.0f, 0.0f};  // NaN -> black, as the clip encoder
  const Rgb inset = apply(kInset, linear);
  const Rgb shaped{curve(inset.r), curve(inset.g), curve(inset.b)};
  const Rgb out = apply(kOutset, shaped);
  return {decode(out.r), decode(out.g), decode(out.b)};
}

float agx_display_channel(float linear) {
  return std::clamp(curve(linear), 0.0f, 1.0f);
}

}  // namespace thaw::render
