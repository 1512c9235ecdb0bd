// slc: the traversal draws leaves with exactly the probabilities its weights give (chi-square
// against the recursively multiplied child probabilities), and the estimator converges to
// exhaustive on the same VPL set (per-pixel z-test).
#include <gtest/gtest.h>

#include "core/math/box_bounds.h"
#include "core/manylight/slc/slc_sampler.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/renderer.h"
#include "core/rng/hash_rng.h"
#include "core/scene/default_scene.h"
#include "core/vpl/vpl_shading.h"
#include "tests/stat_util.h"
#include "tests/core/manylight/many_light_test_util.h"

namespace sst {
namespace {

vec3 random_unit(HashRng& rng) {
  float z = 2.0f * hash_rng_next(rng) - 1.0f, phi = 6.2831853f * hash_rng_next(rng);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// VPLs in the unit cube with random normals (so no two internal nodes share a normal).
VplSet random_vpls(int n, uint32_t seed) {
  HashRng rng = hash_rng(seed, 0, 0);
  VplSet vpls;
  for (int i = 0; i < n; ++i) {
    vec3 p(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
    vec3 normal = random_unit(rng);
    vec3 intensity(0.1f + hash_rng_next(rng), 0.1f + hash_rng_next(rng), 0.1f + hash_rng_next(rng));
    vpls.push_back({p, normal, intensity});
  }
  return vpls;
}

// Inside the VPL cloud, normal tilted: some boxes lie behind the surface (weight 0), some
// contain x (the near rule).
ShadingPoint test_point() {
  ShadingPoint sp;
  sp.p = vec3(0.3f, 0.4f, 0.5f);
  sp.ng = glm::normalize(vec3(0.2f, 0.1f, 1.0f));
  sp.basis = basis_from_normal(sp.ng);
  sp.wo = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
  sp.brdf.diffuse = vec3(0.5f);
  return sp;
}

// Chi-square of observed stop-node frequencies against `probabilities`, with one more bin for
// dead branches (mass 1 - sum); also checks that every draw's P is the exact probability of its
// node and that no zero-probability node is drawn.
void check_frequencies(const LightTree& tree, const ChildWeights& weights, const StopRule& stop,
                       const std::vector<double>& probabilities, int draws) {
  size_t n = tree.node_count();
  std::vector<double> observed(n + 1, 0.0), expected(n + 1);
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    expected[i] = probabilities[i] * draws;
    sum += probabilities[i];
  }
  expected[n] = std::max(0.0, 1.0 - sum) * draws;
  for (int s = 0; s < draws; ++s) {
    PixelSampler walk_ps = pixel_sampler(7, 0, uint32_t(s));
    TreeWalk t = walk_tree(tree, weights, stop, walk_ps);
    if (t.node == kNoNode) {
      observed[n] += 1.0;
      continue;
    }
    ASSERT_GT(probabilities[t.node], 0.0) << "drew node " << t.node << " of probability 0";
    ASSERT_NEAR(probability_value(t.probability), probabilities[t.node], test::walk_tolerance(tree) * probabilities[t.node]);
    observed[t.node] += 1.0;
  }
  int dof = 0;
  double chi2 = test::chi_square_statistic(observed, expected, &dof);
  EXPECT_LT(chi2, test::chi_square_critical_1e6(dof)) << "dof " << dof;
}

// Below the VPL cloud, facing it: every box is above the surface, no branch is dead.
ShadingPoint point_below() {
  ShadingPoint sp = test_point();
  sp.p = vec3(0.5f, 0.4f, -0.3f);
  sp.ng = glm::normalize(vec3(0.1f, 0.0f, 1.0f));
  sp.basis = basis_from_normal(sp.ng);
  return sp;
}

TEST(SlcSampler, LeafProbabilitiesSumToOneAndMatchTraversalFrequencies) {
  VplSet vpls = random_vpls(50, 11);
  ShadingPoint sp = point_below();
  for (const char* kind : {"radix", "perfect", "agglomerative"}) {
    SCOPED_TRACE(kind);
    LightTreeParams params;
    params.tree = kind;
    LightTree tree = build_light_tree(vpls, params);
    std::vector<double> p = stop_probabilities(tree, slc_weights(sp), stop_at_leaves);
    double sum = 0.0;
    int reachable = 0;
    for (size_t i = 0; i < p.size(); ++i) {
      if (p[i] > 0.0) {
        EXPECT_TRUE(tree[uint32_t(i)].is_leaf());
        ++reachable;
      }
      sum += p[i];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_EQ(reachable, 50);
    check_frequencies(tree, slc_weights(sp), stop_at_leaves, p, 200000);
  }
}

TEST(SlcSampler, ZeroWeightsAndDeadBranchesMatchTraversalFrequencies) {
  // Inside the cloud with a tilted normal: boxes behind the surface weigh 0, some subtrees are
  // wholly behind it (dead branches), some boxes contain x (the near rule).
  VplSet vpls = random_vpls(50, 11);
  ShadingPoint sp = test_point();
  for (const char* kind : {"radix", "perfect", "agglomerative"}) {
    SCOPED_TRACE(kind);
    LightTreeParams params;
    params.tree = kind;
    LightTree tree = build_light_tree(vpls, params);
    std::vector<double> p = stop_probabilities(tree, slc_weights(sp), stop_at_leaves);
    int reachable = 0;
    for (double q : p) reachable += q > 0.0;
    EXPECT_GT(reachable, 10);
    EXPECT_LT(reachable, 50);
    check_frequencies(tree, slc_weights(sp), stop_at_leaves, p, 200000);
  }
}

// Unbiasedness, exactly: the estimator's expectation is the sum of c_j over the leaves it can
// reach (c_j / P_j drawn with probability P_j), so it equals exhaustive (without visibility,
// which both trace the same way) iff every VPL with c_j > 0 has P_j > 0.
// The node-distance floor in place of Yuksel's near rule, at the same point inside the cloud:
// the walk still follows its probabilities, reaches the VPLs the near rule reaches, and weighs
// them otherwise.
TEST(SlcSampler, NodeDistanceFloorMatchesTraversalFrequencies) {
  VplSet vpls = random_vpls(50, 11);
  ShadingPoint sp = test_point();
  for (const char* kind : {"radix", "perfect"}) {
    SCOPED_TRACE(kind);
    LightTreeParams params;
    params.tree = kind;
    LightTree tree = build_light_tree(vpls, params);
    std::vector<double> p = stop_probabilities(tree, slc_weights(sp, 0.5f), stop_at_leaves);
    std::vector<double> yuksel = stop_probabilities(tree, slc_weights(sp), stop_at_leaves);
    double moved = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
      EXPECT_EQ(p[i] > 0.0, yuksel[i] > 0.0) << i;
      moved += std::abs(p[i] - yuksel[i]);
    }
    EXPECT_GT(moved, 0.05) << "the floor changed no probability";
    check_frequencies(tree, slc_weights(sp, 0.5f), stop_at_leaves, p, 200000);
  }
}

TEST(SlcSampler, EveryContributingVplIsReachable) {
  HashRng rng = hash_rng(17, 0, 0);
  for (int set = 0; set < 10; ++set) {
    VplSet vpls = random_vpls(40, 100 + set);
    for (const char* kind : {"radix", "perfect", "agglomerative"}) {
      LightTreeParams params;
      params.tree = kind;
      LightTree tree = build_light_tree(vpls, params);
      for (int k = 0; k < 50; ++k) {
        ShadingPoint sp = test_point();
        sp.p = 1.6f * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) - 0.3f;
        sp.ng = glm::normalize(2.0f * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) - 1.0f);
        sp.basis = basis_from_normal(sp.ng);
        std::vector<double> p = stop_probabilities(tree, slc_weights(sp), stop_at_leaves);
        for (uint32_t i = tree.first_leaf; i < tree.first_leaf + tree.leaf_count; ++i) {
          if (tree[i].vpl() == kNoNode) continue;
          vec3 c = vpl_contribution(vpls[tree[i].vpl()], sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, 0.01f);
          if (max_component(c) > 0.0f) { ASSERT_GT(p[i], 0.0) << kind << " leaf " << i; }
        }
      }
    }
  }
}

TEST(SlcSampler, CosineBoundIsConservative) {
  HashRng rng = hash_rng(5, 0, 0);
  for (int i = 0; i < 2000; ++i) {
    vec3 a(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)), b(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
    Bounds3 box{glm::min(a, b), glm::max(a, b)};
    vec3 x = 2.0f * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) - 0.5f;
    vec3 n = random_unit(rng);
    float bound = box_cos_bound(box, x, n);
    ASSERT_TRUE(bound >= 0.0f && bound <= 1.0f);
    for (int k = 0; k < 20; ++k) {
      vec3 y = box.lo + (box.hi - box.lo) * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
      float len = glm::length(y - x);
      if (len > 0.0f) { ASSERT_LE(glm::dot(n, (y - x) / len), bound + 1e-5f); }
    }
    if (!(bound > 0.0f)) { EXPECT_GT(box_distance2_min(box, x), 0.0f); }
  }
}

TEST(SlcSampler, DeadBranchAndSingleLeaf) {
  ShadingPoint sp = test_point();
  // Every VPL far below the tangent plane: the root's children both weigh 0.
  VplSet below = {{vec3(0, 0, -5), vec3(0, 0, 1), vec3(1)}, {vec3(1, 0, -5), vec3(0, 0, 1), vec3(1)}};
  LightTree tree = build_light_tree(below, {});
  PixelSampler ps = pixel_sampler(1, 0, 0);
  TreeWalk t = walk_tree(tree, slc_weights(sp), stop_at_leaves, ps);
  EXPECT_EQ(t.node, kNoNode);
  EXPECT_EQ(probability_value(t.probability), 0.0);
  VplSet first = {below[0]};
  LightTree one = build_light_tree(first, {});
  t = walk_tree(one, slc_weights(sp), stop_at_leaves, ps);
  EXPECT_EQ(t.node, one.root);
  EXPECT_EQ(probability_value(t.probability), 1.0);
  EXPECT_EQ(t.nodes_visited, 1u);
  EXPECT_EQ(divide_by_probability(vec3(1.0f), tree_probability(0.0f)), vec3(0.0f));
  TreeProbability tiny = tree_probability(1.0f);
  tiny.e = -1000;  // 2^-1000, far below float's range
  EXPECT_EQ(divide_by_probability(vec3(1.0f), tiny), vec3(0.0f));  // overflow: 0, not inf
  // The walk keeps P far below float's range exact: 0.5^200 stays 2^-200, so a tiny contribution
  // divided by it is the right finite value, and 1 / P (beyond float's range) is 0, not inf.
  TreeProbability deep = tree_probability(1.0f);
  for (int level = 0; level < 200; ++level) deep = tree_probability_times(deep, 0.5f);
  EXPECT_EQ(probability_value(deep), std::ldexp(1.0, -200));
  EXPECT_EQ(divide_by_probability(vec3(1e-30f), deep), vec3(std::ldexp(1e-30f, 200)));
  EXPECT_EQ(divide_by_probability(vec3(1.0f), deep), vec3(0.0f));
  EXPECT_EQ(divide_by_probability(vec3(0x1p-100f), tree_probability(0x1p-100f)), vec3(1.0f));
}

TEST(SlcSampler, ConvergesToExhaustiveOnTheSameVpls) {
  // Few VPLs and many samples (see many_light_method_test.cpp): per-pixel means near normal.
  Scene scene = load_default_scene();
  nlohmann::json vpl = {{"vpls", 24}, {"vpl_max_bounces", 3}};
  RenderResult slc = render_frame(scene, test::small_options("slc", 1024, 16), vpl);
  RenderResult exhaustive = render_frame(scene, test::small_options("exhaustive", 1024, 16), vpl);
  Image s = test::frame_layer(slc, "indirect"), var = test::frame_layer(slc, "indirect_variance");
  EXPECT_EQ(test::z_test_failures(s, var, test::frame_layer(exhaustive, "indirect"), 5.1), 0);
  EXPECT_EQ(slc.frame.counters.nonfinite_samples, 0u);
  EXPECT_EQ(slc.frame.method_counters["tree"]["kind"], "radix");
  EXPECT_GT(slc.timer.ms("tree_build"), 0.0);
  EXPECT_GT(slc.frame.method_counters["nodes_visited_mean"].get<double>(), 1.0);
}

TEST(SlcSampler, RegisteredWithTreeParams) {
  const MethodInfo& m = find_method("slc");
  bool has_tree = false;
  for (const ParamInfo& p : m.params) has_tree |= p.name == "tree";
  EXPECT_TRUE(has_tree);
  try {
    create_method("slc", {{"v_min", 2.0}});
    ADD_FAILURE() << "v_min 2 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("v_min"), std::string::npos);
  }
  Scene scene = load_default_scene();
  for (const char* kind : {"perfect", "agglomerative"}) {
    RenderResult r = render_frame(scene, test::small_options("slc", 2, 8), {{"vpls", 200}, {"tree", kind}});
    EXPECT_EQ(r.frame.method_counters["tree"]["kind"], kind);
    for (float v : r.frame.color.data) ASSERT_TRUE(std::isfinite(v));
  }
}

}  // namespace
}  // namespace sst
