// lanes4 (core/math/cpu_gpu.h) against the scalar operations it runs side by side, and the
// kernels written with it, box_cos_bound_in_frame and box_cos_bound_pair_in_frame
// (core/math/box_bounds.h), against their scalar form: the shared code's CPU/GPU equality rests on
// these being the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "core/math/box_bounds.h"
#include "core/rng/hash_rng.h"

namespace sst {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

// Values that tell the choices of min and max apart: signed zeros, equal values, infinities.
constexpr float kSpecial[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-38f, -3.5f, std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), 2.5e7f};

TEST(Lanes4, EveryOperationIsTheScalarOneInEachLane) {
  for (float a : kSpecial) {
    for (float b : kSpecial) {
      lanes4 x(a, b, -a, 0.5f * b), y(b, a, -0.0f, b);
      lanes4 sum = x + y, difference = x - y, product = x * y, scaled = a * y, scaled_right = y * b;
      lanes4 low = min(x, y), high = max(x, y), quotient = x / y, root = sqrt(x);
      for (int i = 0; i < 4; ++i) {
        SCOPED_TRACE(testing::Message() << a << " " << b << " lane " << i);
        EXPECT_EQ(bits(sum[i]), bits(x[i] + y[i]));
        EXPECT_EQ(bits(difference[i]), bits(x[i] - y[i]));
        EXPECT_EQ(bits(product[i]), bits(x[i] * y[i]));
        EXPECT_EQ(bits(scaled[i]), bits(a * y[i]));
        EXPECT_EQ(bits(scaled_right[i]), bits(y[i] * b));
        // glm's scalar choices, which the vec3 code these lanes replace made: min(-0, +0) = -0.
        EXPECT_EQ(bits(low[i]), bits(glm::min(x[i], y[i])));
        EXPECT_EQ(bits(high[i]), bits(glm::max(x[i], y[i])));
        // A NaN's payload is the hardware's; that it is a NaN is what the scalar code sees.
        float q = x[i] / y[i], r = std::sqrt(x[i]);
        if (std::isnan(q)) EXPECT_TRUE(std::isnan(quotient[i])); else EXPECT_EQ(bits(quotient[i]), bits(q));
        if (std::isnan(r)) EXPECT_TRUE(std::isnan(root[i])); else EXPECT_EQ(bits(root[i]), bits(r));
      }
    }
  }
}

// box_cos_bound_in_frame as it was written before its lanes: box_corner_dot_range per axis.
float scalar_cos_bound(vec3 lo, vec3 hi, vec3 x, const Basis& frame) {
  if (box_empty(lo, hi)) return 0.0f;
  if (box_inside(lo, hi, x)) return 1.0f;
  vec3 dl = lo - x, dh = hi - x;
  vec2 rx = box_corner_dot_range(dl, dh, frame.t);
  vec2 ry = box_corner_dot_range(dl, dh, frame.b);
  vec2 rz = box_corner_dot_range(dl, dh, frame.n);
  if (!(rz.y > 0.0f)) return 0.0f;
  float dx = box_min_abs(rx.x, rx.y), dy = box_min_abs(ry.x, ry.y);
  float len2 = dx * dx + dy * dy + rz.y * rz.y;
  return len2 > 0.0f ? std::min(1.0f, rz.y / std::sqrt(len2)) : 1.0f;
}

// Both the single bound and the pair (each box with the box drawn before it) against the scalar form.
TEST(Lanes4, BoxCosBoundEqualsItsScalarFormToTheBit) {
  HashRng rng = hash_rng(11, 0, 0);
  auto uniform3 = [&](float scale) {
    return scale * (2.0f * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) - 1.0f);
  };
  int nonzero = 0;
  vec3 previous_lo(0.0f), previous_hi(0.0f);
  for (int i = 0; i < 200000; ++i) {
    vec3 a = uniform3(1.0f), b = uniform3(1.0f);
    // Flat, point and empty boxes, and axis-aligned normals, now and then.
    if (i % 7 == 0) b.z = a.z;
    if (i % 11 == 0) b = a;
    vec3 lo = glm::min(a, b), hi = glm::max(a, b);
    if (i % 13 == 0) std::swap(lo, hi);
    vec3 x = uniform3(1.5f);
    vec3 n = i % 5 == 0 ? vec3(0.0f, 0.0f, i % 10 == 0 ? 1.0f : -1.0f) : glm::normalize(uniform3(1.0f));
    if (!std::isfinite(n.x)) continue;
    Basis frame = basis_from_normal(n);
    float expected = scalar_cos_bound(lo, hi, x, frame);
    ASSERT_EQ(bits(box_cos_bound_in_frame(lo, hi, x, frame)), bits(expected)) << i;
    vec2 pair = box_cos_bound_pair_in_frame(previous_lo, previous_hi, lo, hi, x, frame);
    ASSERT_EQ(bits(pair.x), bits(scalar_cos_bound(previous_lo, previous_hi, x, frame))) << i;
    ASSERT_EQ(bits(pair.y), bits(expected)) << i;
    previous_lo = lo;
    previous_hi = hi;
    nonzero += expected > 0.0f && expected < 1.0f;
  }
  EXPECT_GT(nonzero, 50000);  // the comparison reached the bound's arithmetic, not only its early outs
}

}  // namespace
}  // namespace sst
