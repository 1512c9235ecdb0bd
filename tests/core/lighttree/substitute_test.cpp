// SST substitutes (substitute.h): single merges against the equations, and every node of built
// trees against the direct computation over its subtree's leaves.
#include "core/lighttree/substitute.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "tests/core/lighttree/lighttree_test_util.h"

namespace sst {
namespace {

using test::leaves_below;
using test::reachable_nodes;

constexpr SubstituteThresholds kThresholds{0.5f, 0.1f};

LightNode leaf(vec3 p, vec3 n, float grey) { return make_leaf({p, n, vec3(grey)}, 0, kThresholds); }

LightNode merged(const LightNode& a, const LightNode& b, SubstituteThresholds t = kThresholds) {
  return merge_children(a, 1, b, 2, t);
}

TEST(Sst, TwoLeavesFollowEquationsOneToThree) {
  vec3 up(0, 0, 1);
  LightNode p = merged(leaf(vec3(0, 0, 0), up, 1.0f), leaf(vec3(2, 0, 0), up, 3.0f));
  EXPECT_EQ(p.mean, vec3(1.5f, 0, 0));  // (1 * 0 + 3 * 2) / 4
  EXPECT_EQ(p.normal, up);
  // basis_from_normal(+z) has t = +x: s2.x = (1 * 1.5^2 + 3 * 0.5^2) / 4.
  EXPECT_FLOAT_EQ(p.variance.x, 0.75f);
  EXPECT_EQ(p.variance.y, 0.0f);
  EXPECT_EQ(p.variance.z, 0.0f);
  EXPECT_EQ(p.similarity, 1.0f);
  EXPECT_EQ(p.sigma_z, 0.0f);
  EXPECT_TRUE(p.suitable());
  EXPECT_FALSE(p.is_leaf());
  EXPECT_EQ(p.left, 1u);
  EXPECT_EQ(p.right, 2u);
  // One VPL above the other along the shared normal: all the spread is along z.
  LightNode q = merged(leaf(vec3(0, 0, 0), up, 1.0f), leaf(vec3(0, 0, 0.4f), up, 1.0f));
  EXPECT_FLOAT_EQ(q.variance.z, 0.04f);
  EXPECT_FLOAT_EQ(q.sigma_z, 0.2f);
  EXPECT_FALSE(q.suitable()) << "sigma_z 0.2 > sigma_max 0.1";
  EXPECT_TRUE(merged(leaf(vec3(0), up, 1.0f), leaf(vec3(0, 0, 0.4f), up, 1.0f), {0.5f, 0.2f}).suitable());
}

TEST(Sst, NormalSimilarityMultipliesDownTheTree) {
  vec3 n1(0, 0, 1), n2 = glm::normalize(vec3(1, 0, 1));
  LightNode a = merged(leaf(vec3(0), n1, 1.0f), leaf(vec3(1, 0, 0), n2, 1.0f));
  EXPECT_NEAR(a.similarity, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(glm::dot(a.normal, glm::normalize(n1 + n2)), 1.0f, 1e-6f);
  LightNode b = merged(a, a);
  EXPECT_NEAR(b.similarity, 0.5f, 1e-6f) << "v1 v2 max(n.n, 0) = 0.707 * 0.707 * 1";
  EXPECT_TRUE(merged(a, a, {0.49f, 1.0f}).suitable());
  EXPECT_FALSE(merged(a, a, {0.51f, 1.0f}).suitable());
}

TEST(Sst, OppositeNormalsFallBackToTheHeavierChild) {
  vec3 up(0, 0, 1), down(0, 0, -1);
  LightNode tie = merged(leaf(vec3(0), up, 1.0f), leaf(vec3(1, 0, 0), down, 1.0f));
  EXPECT_EQ(tie.normal, up) << "equal weights: the first child";
  EXPECT_EQ(tie.similarity, 0.0f);
  EXPECT_FALSE(tie.suitable());
  EXPECT_TRUE(is_finite(tie.variance));
  LightNode heavy = merged(leaf(vec3(0), up, 1.0f), leaf(vec3(1, 0, 0), down, 2.0f));
  EXPECT_NEAR(glm::dot(heavy.normal, down), 1.0f, 1e-6f) << "1 up + 2 down does not cancel";
  // Almost cancelling: below the 1e-4 relative threshold the heavier child's normal is used.
  vec3 tilted = glm::normalize(vec3(1e-6f, 0, -1));
  LightNode nearly = merged(leaf(vec3(0), up, 1.0f), leaf(vec3(0), tilted, 1.0f + 1e-7f));
  EXPECT_EQ(nearly.normal, tilted);
}

TEST(Sst, ZeroWeightGivesMidpointAndZeroVariance) {
  vec3 up(0, 0, 1);
  LightNode p = merged(leaf(vec3(0), up, 0.0f), leaf(vec3(2, 4, 0), up, 0.0f));
  EXPECT_EQ(p.mean, vec3(1, 2, 0));
  EXPECT_EQ(p.variance, vec3(0.0f));
  EXPECT_EQ(p.normal, up);
  // Zero weights and opposite normals together.
  LightNode q = merged(leaf(vec3(0), up, 0.0f), leaf(vec3(2, 4, 0), -up, 0.0f));
  EXPECT_EQ(q.normal, up);
  EXPECT_TRUE(is_finite(q.mean) && is_finite(q.variance));
  // One black child: the other's distribution, exactly.
  LightNode r = merged(leaf(vec3(0), up, 0.0f), leaf(vec3(2, 4, 0), up, 5.0f));
  EXPECT_EQ(r.mean, vec3(2, 4, 0));
  EXPECT_EQ(r.variance, vec3(0.0f));
}

TEST(Sst, EmptyChildrenPassTheOtherSubstituteUp) {
  LightNode pad = make_padding_leaf(kThresholds);
  LightNode a = merged(leaf(vec3(0), vec3(0, 0, 1), 1.0f), leaf(vec3(1, 0, 0), vec3(0, 1, 0), 1.0f));
  LightNode p = merged(a, pad);
  EXPECT_EQ(p.mean, a.mean);
  EXPECT_EQ(p.normal, a.normal);
  EXPECT_EQ(p.variance, a.variance);
  EXPECT_EQ(p.similarity, a.similarity);
  EXPECT_EQ(p.bounds_lo, a.bounds_lo);
  EXPECT_EQ(p.bounds_hi, a.bounds_hi);
  LightNode both = merged(pad, pad);
  EXPECT_TRUE(both.empty());
  EXPECT_TRUE(both.bounds().empty());
  EXPECT_EQ(both.intensity, vec3(0.0f));
}

// Direct computation over a subtree's leaves, in double: weights c_j = luminance, mean,
// trace of the covariance, and the covariance's diagonal in the frame of `normal`.
struct Direct {
  double weight = 0.0;
  dvec3 mean{0.0};
  double trace = 0.0;
  dvec3 diagonal{0.0};
};

Direct direct(const LightTree& tree, uint32_t node) {
  std::vector<uint32_t> leaves = leaves_below(tree, node);
  Direct d;
  for (uint32_t l : leaves) {
    double c = luminance(tree[l].intensity);
    d.weight += c;
    d.mean += c * dvec3(tree[l].mean);
  }
  if (d.weight == 0.0) return d;
  d.mean /= d.weight;
  Basis basis = basis_from_normal(tree[node].normal);
  dvec3 t(basis.t), b(basis.b), n(basis.n);
  for (uint32_t l : leaves) {
    double c = luminance(tree[l].intensity) / d.weight;
    dvec3 off = dvec3(tree[l].mean) - d.mean;
    d.trace += c * glm::dot(off, off);
    dvec3 local(glm::dot(off, t), glm::dot(off, b), glm::dot(off, n));
    d.diagonal += c * local * local;
  }
  return d;
}

// Tolerances. Each merge rounds the mean to float, an error of a few ulp of the coordinates'
// magnitude |p|; over a path of h merges (h up to the tree height, ~40 for these radix trees)
// that adds up to about 3 h 2^-24 |p| < 1e-5 |p|. The variance is a sum of squares of
// offsets, so it has no cancellation: its error is the same relative rounding times D^2,
// plus 2 |d| times the mean error.
struct Tolerance {
  double mean, variance;
};

Tolerance tolerance(const LightTree& tree, double max_coordinate) {
  double d = tree.length_scale;
  double mean = 1e-5 * (max_coordinate + d);
  return {mean, 1e-5 * d * d + 4.0 * d * mean};
}

class SstTrees : public ::testing::TestWithParam<std::string> {};

TEST_P(SstTrees, MeanAndTraceEqualTheDirectComputation) {
  for (vec3 offset : {vec3(0.0f), vec3(-40.0f, 7.0f, 90.0f)}) {
    VplSet vpls = test::random_vpls(1500, 100, 2.0f, offset);
    for (size_t i = 0; i < vpls.size(); i += 7) vpls[i].intensity = vec3(0.0f);  // some black VPLs
    LightTreeParams params;
    params.tree = GetParam();
    LightTree tree = build_light_tree(vpls, params);
    Tolerance tol = tolerance(tree, glm::length(offset) + 4.0);
    double worst_mean = 0.0, worst_trace = 0.0;
    for (uint32_t i : reachable_nodes(tree)) {
      const LightNode& n = tree[i];
      if (n.is_leaf() || n.empty()) continue;
      Direct d = direct(tree, i);
      if (d.weight == 0.0) continue;  // all black: midpoint, by definition not the direct mean
      double mean_error = glm::length(dvec3(n.mean) - d.mean);
      double trace_error = std::abs(double(n.variance.x) + n.variance.y + n.variance.z - d.trace);
      worst_mean = std::max(worst_mean, mean_error);
      worst_trace = std::max(worst_trace, trace_error);
      ASSERT_LE(mean_error, tol.mean) << "node " << i;
      ASSERT_LE(trace_error, tol.variance) << "node " << i;
      // The per-axis split is the paper's approximation when normals differ: only bounded.
      for (int k = 0; k < 3; ++k) ASSERT_LE(n.variance[k], d.trace + tol.variance) << "node " << i;
    }
    std::printf("%s offset %.0f: worst mean error %.3g (tol %.3g), worst trace error %.3g (tol %.3g)\n",
                GetParam().c_str(), glm::length(offset), worst_mean, tol.mean, worst_trace, tol.variance);
  }
}

// All VPLs share one normal (not axis-aligned, so the frame is a general rotation), on a plane
// with a little spread along the normal: every frame in the tree is the same, and each variance
// component is exact, not only the trace.
TEST_P(SstTrees, EveryComponentIsExactWhenAllNormalsAgree) {
  vec3 normal = glm::normalize(vec3(1.0f, 2.0f, 3.0f));
  Basis basis = basis_from_normal(normal);
  std::mt19937 rng(101);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  VplSet vpls;
  for (int i = 0; i < 1500; ++i) {
    vec3 p = vec3(3.0f, -1.0f, 2.0f) + to_world(basis, vec3(u(rng), 0.5f * u(rng), 0.01f * u(rng)));
    vpls.push_back({p, normal, vec3(0.5f + 0.5f * u(rng))});
  }
  LightTreeParams params;
  params.tree = GetParam();
  LightTree tree = build_light_tree(vpls, params);
  Tolerance tol = tolerance(tree, 6.0);
  size_t suitable = 0, internal = 0;
  for (uint32_t i : reachable_nodes(tree)) {
    const LightNode& n = tree[i];
    if (n.is_leaf() || n.empty()) continue;
    ++internal;
    ASSERT_NEAR(glm::dot(n.normal, normal), 1.0f, 1e-6f);
    Direct d = direct(tree, i);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(n.variance[k], d.diagonal[k], tol.variance) << "node " << i << " axis " << k;
    ASSERT_NEAR(n.sigma_z, std::sqrt(d.diagonal.z), 1e-4 * tree.length_scale);
    suitable += n.suitable();
  }
  // sigma_z <= 0.01 / sqrt(3) ~ 0.006 against sigma_max * D = 0.005 * ~2.5: all suitable.
  EXPECT_EQ(suitable, internal);
}

// With differing normals the per-axis split is approximate: eq. 2 reuses each child's s2 in
// the child's own frame. The error of s2.z has a bound that follows from the merge itself. Let
// Sigma_i be child i's exact covariance, n_i its normal, n the parent's, theta_i the angle
// between them, w_i = c_i / (c1 + c2). The offsets d_i are exact (parallel-axis theorem along
// any axis), so the parent's error against the exact variance along n is
//   e = sum_i w_i (e_i + n_i' Sigma_i n_i - n' Sigma_i n),
// and |a' S a - b' S b| = |(a - b)' S (a + b)| <= lambda_max |a - b| |a + b| = lambda_max 2 sin(theta)
// for unit a, b, also <= lambda_max, with lambda_max <= trace(Sigma_i). Hence
//   |e| <= B = sum_i w_i (B_i + min(2 sin theta_i, 1) trace(Sigma_i)),   B = 0 at leaves.
// The test computes exact moments and B bottom-up in double and checks |s2.z - exact| <= B
// plus float rounding, on a curved surface (a sphere cap: normals vary smoothly) and on random
// VPLs.
struct Moments {
  double weight = 0.0;
  dvec3 first{0.0};
  glm::dmat3 second{0.0};
  double bound = 0.0;
  dvec3 mean() const { return first / weight; }
  glm::dmat3 covariance() const {
    dvec3 m = mean();
    return second / weight - glm::outerProduct(m, m);
  }
  double trace() const {
    glm::dmat3 c = covariance();
    return c[0][0] + c[1][1] + c[2][2];
  }
};

VplSet sphere_cap_vpls(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  VplSet vpls;
  while (vpls.size() < n) {
    vec3 d = test::random_unit(rng);
    if (d.z < 0.3f) continue;  // a cap of ~73 degrees around +z, radius 2
    vpls.push_back({2.0f * d, d, vec3(0.2f + u(rng))});
  }
  return vpls;
}

TEST_P(SstTrees, NormalVarianceStaysWithinTheMergeBound) {
  for (int scene = 0; scene < 2; ++scene) {
    VplSet vpls = scene == 0 ? sphere_cap_vpls(2000, 102) : test::random_vpls(1500, 103);
    LightTreeParams params;
    params.tree = GetParam();
    LightTree tree = build_light_tree(vpls, params);
    Tolerance tol = tolerance(tree, 4.0);
    std::vector<Moments> moments(tree.node_count());
    std::vector<uint32_t> order = reachable_nodes(tree);  // parents before children
    double worst_ratio = 0.0, worst_error = 0.0;
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
      const LightNode& n = tree[*it];
      Moments& m = moments[*it];
      if (n.is_leaf()) {
        if (n.empty()) continue;
        dvec3 p(n.mean);
        double c = luminance(n.intensity);
        m = {c, c * p, c * glm::outerProduct(p, p), 0.0};
        continue;
      }
      const Moments &a = moments[n.left], &b = moments[n.right];
      m = {a.weight + b.weight, a.first + b.first, a.second + b.second, 0.0};
      if (m.weight == 0.0) continue;
      for (uint32_t child : {n.left, n.right}) {
        const Moments& cm = moments[child];
        if (cm.weight == 0.0) continue;
        float cos_theta = std::clamp(glm::dot(tree[child].normal, n.normal), -1.0f, 1.0f);
        double sin_theta = std::sqrt(std::max(0.0, 1.0 - double(cos_theta) * cos_theta));
        m.bound += cm.weight / m.weight * (cm.bound + std::min(2.0 * sin_theta, 1.0) * cm.trace());
      }
      dvec3 axis(n.normal);
      double exact = glm::dot(axis, m.covariance() * axis);
      double error = std::abs(double(n.variance.z) - exact);
      ASSERT_LE(error, m.bound + tol.variance) << "node " << *it;
      worst_error = std::max(worst_error, error);
      if (m.bound > tol.variance) worst_ratio = std::max(worst_ratio, error / m.bound);
    }
    std::printf("%s %s: worst |s2.z - exact| %.3g, worst error / bound %.3f\n", GetParam().c_str(),
                scene == 0 ? "sphere cap" : "random", worst_error, worst_ratio);
  }
}

// On the walls of a room a node with v >= v_min lies on one wall (merges across a 90-degree
// corner have v = 0), so its s2.z is exact: the suitability test sees the real flatness.
TEST_P(SstTrees, SuitableNodesOfARoomLieOnOneWall) {
  VplSet vpls = test::room_vpls(3000, 104);
  LightTreeParams params;
  params.tree = GetParam();
  LightTree tree = build_light_tree(vpls, params);
  size_t suitable = 0;
  for (uint32_t i : reachable_nodes(tree)) {
    const LightNode& n = tree[i];
    if (n.is_leaf() || n.empty() || !n.suitable()) continue;
    ++suitable;
    for (uint32_t l : leaves_below(tree, i)) ASSERT_EQ(tree[l].normal, n.normal) << "node " << i;
    ASSERT_EQ(n.variance.z, 0.0f);
  }
  EXPECT_GT(suitable, 1000u);
}

INSTANTIATE_TEST_SUITE_P(Sst, SstTrees, ::testing::Values("radix", "perfect", "agglomerative"));

}  // namespace
}  // namespace sst
