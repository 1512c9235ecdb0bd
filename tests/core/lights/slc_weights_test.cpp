// slc_pair_weights (core/lights/slc_weights.h), whose two boxes' bounds and divisions run side by
// side in lanes, against its one-box-at-a-time form, to the bit: slc's walks and the emitter
// tree's slc light sampler on both backends take their choices from these weights.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <utility>

#include "core/lights/slc_weights.h"
#include "core/rng/hash_rng.h"

namespace sst {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

// The weights one box at a time, as they were written before the pair: box_cos_bound_in_frame
// per box (itself held to its scalar form by Lanes4.BoxCosBoundEqualsItsScalarFormToTheBit).
vec2 weights_one_box_at_a_time(vec3 lo0, vec3 hi0, float lum0, bool empty0, vec3 lo1, vec3 hi1, float lum1,
                               bool empty1, vec3 x, const Basis& frame) {
  float base[2], d2[2];
  bool near = false;
  for (int k = 0; k < 2; ++k) {
    vec3 lo = k == 0 ? lo0 : lo1, hi = k == 0 ? hi0 : hi1;
    bool empty = k == 0 ? empty0 : empty1;
    float b = (k == 0 ? lum0 : lum1) * box_cos_bound_in_frame(lo, hi, x, frame);
    base[k] = empty ? 0.0f : b;
    d2[k] = empty ? 0.0f : box_distance2_min(lo, hi, x);
    if (!empty && d2[k] <= box_diagonal2(lo, hi)) near = true;
  }
  if (near) return vec2(base[0], base[1]);
  return vec2(base[0] > 0.0f ? base[0] / d2[0] : 0.0f, base[1] > 0.0f ? base[1] / d2[1] : 0.0f);
}

TEST(SlcWeights, PairWeightsEqualTheirScalarFormToTheBit) {
  HashRng rng = hash_rng(17, 0, 0);
  auto uniform3 = [&](float scale) {
    return scale * (2.0f * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) - 1.0f);
  };
  auto box = [&](int i, vec3& lo, vec3& hi) {
    vec3 c = uniform3(4.0f), a = c + uniform3(0.5f), b = c + uniform3(0.5f);
    if (i % 7 == 0) b.z = a.z;  // flat
    if (i % 11 == 0) b = a;     // a point, as a leaf
    lo = glm::min(a, b);
    hi = glm::max(a, b);
    if (i % 13 == 0) std::swap(lo, hi);  // empty
  };
  int divided = 0, near = 0;
  for (int i = 0; i < 200000; ++i) {
    vec3 lo0, hi0, lo1, hi1;
    box(i, lo0, hi0);
    box(i / 3, lo1, hi1);
    float lum0 = hash_rng_next(rng), lum1 = i % 17 == 0 ? 0.0f : hash_rng_next(rng);
    bool empty0 = box_empty(lo0, hi0) || i % 19 == 0, empty1 = box_empty(lo1, hi1);
    vec3 x = uniform3(5.0f);
    vec3 n = i % 5 == 0 ? vec3(0.0f, 0.0f, i % 10 == 0 ? 1.0f : -1.0f) : glm::normalize(uniform3(1.0f));
    if (!std::isfinite(n.x)) continue;
    Basis frame = basis_from_normal(n);
    vec2 expected = weights_one_box_at_a_time(lo0, hi0, lum0, empty0, lo1, hi1, lum1, empty1, x, frame);
    vec2 w = slc_pair_weights(lo0, hi0, lum0, empty0, lo1, hi1, lum1, empty1, x, frame, 0.0f);
    ASSERT_EQ(bits(w.x), bits(expected.x)) << i;
    ASSERT_EQ(bits(w.y), bits(expected.y)) << i;
    bool is_near = (!empty0 && box_distance2_min(lo0, hi0, x) <= box_diagonal2(lo0, hi0)) ||
                   (!empty1 && box_distance2_min(lo1, hi1, x) <= box_diagonal2(lo1, hi1));
    near += is_near;
    divided += !is_near && expected.x > 0.0f && expected.y > 0.0f;
  }
  // Both branches were reached, the divided weights often.
  EXPECT_GT(near, 1000);
  EXPECT_GT(divided, 50000);
}

}  // namespace
}  // namespace sst
