// tree_walk_step (core/manylight/estimator.h): one uniform rescaled across a walk's choices, drawn
// afresh only when its remaining bits run low, and choices that follow their probabilities.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/manylight/estimator.h"

namespace sst {
namespace {

// A node whose children are nodes 1 (left) and 2 (right); the walk's own position is not read.
LightNode two_children() {
  LightNode node{};
  node.left = 1;
  node.right = 2;
  return node;
}

TEST(TreeWalk, OneUniformServesChoicesUntilItsBitsRunLow) {
  const LightNode node = two_children();
  PixelSampler ps = pixel_sampler(3, 7, 0);
  TreeWalk walk = tree_walk_begin(0);
  // Even choices: the uniform's choices since its draw have probability P = 2^-k after k of them,
  // and the next one (q = 1/2) draws when P q < 2^-16, at P = 2^-16: 16 choices per draw.
  for (int k = 0; k < 16; ++k) {
    tree_walk_step(walk, node, vec2(1.0f, 1.0f), ps);
    EXPECT_EQ(ps.sets_used, 1u) << k;
  }
  tree_walk_step(walk, node, vec2(1.0f, 1.0f), ps);
  EXPECT_EQ(ps.sets_used, 2u);
  EXPECT_EQ(walk.probability.m, std::ldexp(1.0f, -17));
  // A child of probability 2^-20 is below any rescaled uniform's grain: every such choice draws.
  for (int k = 0; k < 3; ++k) {
    tree_walk_step(walk, node, vec2(1.0f, 1048575.0f), ps);
    EXPECT_EQ(ps.sets_used, 3u + uint32_t(k));
  }
  // A child of weight 0 is never taken, and the choice takes no uniform.
  const uint32_t used = ps.sets_used;
  tree_walk_step(walk, node, vec2(0.0f, 2.0f), ps);
  EXPECT_EQ(walk.node, 2u);
  tree_walk_step(walk, node, vec2(3.0f, 0.0f), ps);
  EXPECT_EQ(walk.node, 1u);
  EXPECT_EQ(ps.sets_used, used);
}

// Over many pixels, 40 choices in a row: each left with probability p, every choice and each
// pair of consecutive ones at their frequencies, as independent choices would give (the rescaled
// uniform is exact in real arithmetic; this checks that its float form and the fresh draws keep
// it so). Tolerances: 5 binomial standard deviations.
TEST(TreeWalk, RescaledChoicesFollowTheirProbabilitiesAndAreIndependent) {
  const LightNode node = two_children();
  constexpr int kWalks = 40000, kSteps = 40;
  for (float p : {0.5f, 0.3f, 0.02f}) {
    std::vector<int> left(kSteps, 0), both(kSteps, 0);
    for (int w = 0; w < kWalks; ++w) {
      PixelSampler ps = pixel_sampler(1, uint32_t(w), 0);
      TreeWalk walk = tree_walk_begin(0);
      bool previous = false;
      for (int k = 0; k < kSteps; ++k) {
        tree_walk_step(walk, node, vec2(p, 1.0f - p), ps);
        bool is_left = walk.node == 1u;
        left[k] += is_left;
        if (k > 0) both[k] += is_left && previous;
        previous = is_left;
      }
    }
    for (int k = 0; k < kSteps; ++k) {
      SCOPED_TRACE(testing::Message() << "p " << p << " choice " << k);
      EXPECT_NEAR(double(left[k]) / kWalks, p, 5.0 * std::sqrt(p * (1.0 - p) / kWalks));
      if (k > 0) {
        double pp = double(p) * p;
        EXPECT_NEAR(double(both[k]) / kWalks, pp, 5.0 * std::sqrt(pp * (1.0 - pp) / kWalks));
      }
    }
  }
}

}  // namespace
}  // namespace sst
