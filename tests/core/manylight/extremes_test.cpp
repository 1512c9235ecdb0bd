// Extremes (acceptance 3): every many-light method of the list, rendered with extreme scene
// scales, VPL counts, tree/cut/block/interleave parameters and sample counts, either finishes with
// all-finite pixels in every layer (color, direct, indirect, indirect_variance, ...) and no
// discarded non-finite samples, or throws sst::Error naming the offending parameter. One axis
// varies at a time from a per-method base, plus the scale axis for every method; a parameter's
// cases run for every method that has the parameter. Degenerate VPL sets that a
// render cannot produce on demand (all VPLs at one point, zero intensities) are tested at the
// sampler level on hand-made sets.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/block_cuts.h"
#include "core/manylight/hybrid/hybrid_sampler.h"
#include "core/manylight/rtslc/rtslc_sampler.h"
#include "core/manylight/slc/slc_sampler.h"
#include "core/manylight/sst/sst_sampler.h"
#include "core/pipeline/renderer.h"
#include "core/rng/hash_rng.h"
#include "core/rng/sobol_sampler.h"
#include "core/scene/default_scene.h"
#include "core/util/error.h"
#include "core/vpl/vpl_shading.h"
#include "tests/analytic_scenes.h"
#include "tests/core/manylight/many_light_test_util.h"

namespace sst {
namespace {

// ---------------------------------------------------------------------------------------------
// Render level

struct ExtremeCase {
  std::string method;
  std::string name;       // readable suffix of the test name
  nlohmann::json params;  // method parameters (vpls added from the base unless given)
  int width = 6;
  int spp = 2;
  float scale = 1.0f;
  bool diffuse_only = true;
  std::string key;  // the parameter an sst::Error must name ("" = any error is a failure)
};

std::string sanitize(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

std::vector<ExtremeCase> all_cases() {
  std::vector<ExtremeCase> cases;
  for (const std::string& m : test::many_light_method_names()) {
    auto has = [&m](const char* key) { return test::has_param(m, key); };
    auto add = [&](std::string name, nlohmann::json p, std::string key, int width = 6, int spp = 2, float scale = 1.0f,
                   bool diffuse_only = true) {
      if (!p.contains("vpls")) p["vpls"] = 200;
      cases.push_back({m, sanitize(name), p, width, spp, scale, diffuse_only, key});
    };
    add("base", nlohmann::json::object(), "");
    // Scale axis (all methods).
    add("scale_1em3", nlohmann::json::object(), "", 6, 2, 1e-3f);
    add("scale_1e4", nlohmann::json::object(), "", 6, 2, 1e4f);
    add("scale_1em3_vpls_3", {{"vpls", 3}}, "vpls", 6, 2, 1e-3f);
    add("scale_1e4_vpls_3", {{"vpls", 3}}, "vpls", 6, 2, 1e4f);
    // VPL counts.
    for (int n : {1, 2, 3, 1000}) add("vpls_" + std::to_string(n), {{"vpls", n}}, "vpls");
    add("vpls_65537", {{"vpls", 65537}}, "vpls", 4, 1);
    add("vpls_1_bounces_1", {{"vpls", 1}, {"vpl_max_bounces", 1}}, "vpl_max_bounces");
    // Sample counts.
    add("spp_1", nlohmann::json::object(), "", 6, 1);
    add("spp_256", {{"vpls", 50}}, "", 4, 256);
    // Glossy materials (not diffuse_only).
    add("glossy", nlohmann::json::object(), "", 6, 2, 1.0f, false);
    if (has("v_min")) {
      add("v_min_0", {{"v_min", 0.0}}, "v_min");
      add("v_min_1", {{"v_min", 1.0}}, "v_min");
      add("sigma_max_0", {{"sigma_max", 0.0}}, "sigma_max");
      add("sigma_max_1e6", {{"sigma_max", 1e6}}, "sigma_max");
      add("v_min_0_sigma_max_1e6_vpls_1000", {{"v_min", 0.0}, {"sigma_max", 1e6}, {"vpls", 1000}}, "sigma_max");
    }
    if (has("substitutes")) {
      add("substitutes_false", {{"substitutes", false}}, "substitutes");
      add("distance_floor_0", {{"distance_floor", 0.0}}, "distance_floor");
      add("distance_floor_0_scale_1em3", {{"distance_floor", 0.0}}, "distance_floor", 6, 2, 1e-3f);
    }
    if (has("block_size")) {
      add("block_size_1", {{"block_size", 1}}, "block_size");
      add("block_size_1000", {{"block_size", 1000}}, "block_size");
      add("cut_size_1", {{"cut_size", 1}}, "cut_size");
      add("cut_size_32", {{"cut_size", 32}}, "cut_size");
      add("cut_size_32_vpls_3", {{"cut_size", 32}, {"vpls", 3}}, "cut_size");
      add("cut_size_32_block_size_1", {{"cut_size", 32}, {"block_size", 1}}, "cut_size");
    }
    if (has("interleave")) {
      for (int r : {1, 2, 4}) add("interleave_" + std::to_string(r), {{"interleave", r}}, "interleave", 8);
      add("interleave_4_cut_size_1", {{"interleave", 4}, {"cut_size", 1}}, "interleave", 8);
      add("interleave_4_vpls_1", {{"interleave", 4}, {"vpls", 1}}, "interleave", 8);
    }
    if (has("n_min")) {
      add("n_min_1", {{"n_min", 1.0}}, "n_min");
      add("n_min_m1_d_max_10", {{"n_min", -1.0}, {"d_max", 10.0}}, "d_max");
    }
  }
  return cases;
}

void PrintTo(const ExtremeCase& c, std::ostream* os) { *os << c.method << " " << c.name << " " << c.params.dump(); }

class Extremes : public testing::TestWithParam<ExtremeCase> {};

TEST_P(Extremes, FiniteOrNamedError) {
  const ExtremeCase& c = GetParam();
  Scene scene = load_default_scene();
  if (c.scale != 1.0f) test::scale_scene(scene, c.scale);
  RenderOptions o;
  o.method = c.method;
  o.width = o.height = c.width;
  o.spp = c.spp;
  o.diffuse_only = c.diffuse_only;
  o.seed = 5;
  SCOPED_TRACE(c.method + " " + c.params.dump() + " scale " + std::to_string(c.scale) + " spp " +
               std::to_string(c.spp));
  RenderResult r;
  try {
    r = render_frame(scene, o, c.params);
  } catch (const Error& e) {
    std::string what = e.what();
    ASSERT_FALSE(c.key.empty()) << "unexpected sst::Error: " << what;
    EXPECT_NE(what.find(c.key), std::string::npos) << "error does not name " << c.key << ": " << what;
    return;
  }
  EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
  EXPECT_GT(r.frame.counters.samples, 0u);
  bool has_variance = false;
  for (const Layer& l : r.frame.layers()) {
    if (l.name == "indirect_variance") has_variance = true;
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < l.image.data.size(); ++i)
      if (!std::isfinite(l.image.data[i]) && bad++ == 0) first = i;
    EXPECT_EQ(bad, 0u) << "layer " << l.name << ": " << bad << " non-finite values, first at " << first << " = "
                       << (bad ? l.image.data[first] : 0.0f);
  }
  EXPECT_TRUE(has_variance);
  ASSERT_FALSE(r.frame.color.data.empty());
  for (float v : r.frame.color.data) ASSERT_GE(v, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Methods, Extremes, testing::ValuesIn(all_cases()),
                         [](const testing::TestParamInfo<ExtremeCase>& info) {
                           return info.param.method + "_" + info.param.name;
                         });

// Bad values of the parameters above: an sst::Error naming the parameter, never a crash.
struct BadCase {
  std::string method;
  std::string name;
  nlohmann::json params;
  std::string key;
  bool must_throw = true;  // false: a finite render is an acceptable answer too
};

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases;
  for (const std::string& m : test::many_light_method_names()) {
    auto has = [&m](const char* key) { return test::has_param(m, key); };
    cases.push_back({m, "vpls_0", {{"vpls", 0}}, "vpls", false});
    cases.push_back({m, "vpls_m1", {{"vpls", -1}}, "vpls"});
    if (has("v_min")) {
      cases.push_back({m, "v_min_m0_1", {{"v_min", -0.1}}, "v_min"});
      cases.push_back({m, "v_min_1_1", {{"v_min", 1.1}}, "v_min"});
      cases.push_back({m, "sigma_max_m1", {{"sigma_max", -1.0}}, "sigma_max"});
    }
    if (has("cut_size")) {
      cases.push_back({m, "cut_size_0", {{"cut_size", 0}}, "cut_size"});
      cases.push_back({m, "cut_size_33", {{"cut_size", 33}}, "cut_size"});
      cases.push_back({m, "block_size_0", {{"block_size", 0}}, "block_size"});
    }
    if (has("interleave")) {
      cases.push_back({m, "interleave_0", {{"interleave", 0}}, "interleave"});
      cases.push_back({m, "interleave_3", {{"interleave", 3}}, "interleave"});
      cases.push_back({m, "interleave_8", {{"interleave", 8}}, "interleave"});
    }
  }
  return cases;
}

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.method << " " << c.params.dump(); }

class ExtremesBadParams : public testing::TestWithParam<BadCase> {};

TEST_P(ExtremesBadParams, ThrowsErrorNamingTheParameter) {
  const BadCase& c = GetParam();
  RenderOptions o;
  o.method = c.method;
  o.width = o.height = 4;
  o.spp = 1;
  o.diffuse_only = true;
  try {
    RenderResult r = render_frame(load_default_scene(), o, c.params);
    // Accepted: then it must at least render finitely.
    EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
    for (float v : r.frame.color.data) ASSERT_TRUE(std::isfinite(v));
    if (c.must_throw) ADD_FAILURE() << c.method << " accepted " << c.params.dump() << " without an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(c.key), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, ExtremesBadParams, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<BadCase>& info) {
                           return info.param.method + "_" + info.param.name;
                         });

// ---------------------------------------------------------------------------------------------
// Sampler level: hand-made degenerate VPL sets.

constexpr float kClamp = 0.01f;

struct VplSetCase {
  std::string name;
  VplSet vpls;
};

std::vector<VplSetCase> vpl_set_cases() {
  std::vector<VplSetCase> sets;
  Vpl at{vec3(0.2f, 0.3f, 0.4f), vec3(0, 1, 0), vec3(0.5f)};
  sets.push_back({"one_point_1", VplSet(1, at)});
  sets.push_back({"one_point_2", VplSet(2, at)});
  sets.push_back({"one_point_3", VplSet(3, at)});
  sets.push_back({"one_point_1000", VplSet(1000, at)});
  sets.push_back({"one_point_65537", VplSet(65537, at)});
  Vpl zero{vec3(0.2f, 0.3f, 0.4f), vec3(0, 1, 0), vec3(0.0f)};
  sets.push_back({"zero_intensity_1", VplSet(1, zero)});
  sets.push_back({"zero_intensity_one_point_64", VplSet(64, zero)});
  HashRng rng = hash_rng(7, 0, 0);
  VplSet spread_zero, mixed, opposite;
  for (int i = 0; i < 64; ++i) {
    vec3 p(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
    vec3 n = glm::normalize(vec3(hash_rng_next(rng) - 0.5f, hash_rng_next(rng) - 0.5f, hash_rng_next(rng) - 0.5f) + vec3(0, 0, 1e-3f));
    spread_zero.push_back({p, n, vec3(0.0f)});
    mixed.push_back({p, n, i % 2 ? vec3(0.0f) : vec3(0.5f)});
    opposite.push_back({vec3(0.5f), vec3(0, 0, i % 2 ? 1.0f : -1.0f), vec3(1.0f)});
  }
  sets.push_back({"zero_intensity_spread_64", spread_zero});
  sets.push_back({"half_zero_intensity_64", mixed});
  sets.push_back({"one_point_opposite_normals_64", opposite});
  return sets;
}

std::vector<ShadingPoint> shading_points(const VplSet& vpls) {
  std::vector<ShadingPoint> points;
  vec3 c = vpls[0].position;
  struct P {
    vec3 p, n;
  };
  // At the VPL itself (distance 0), just in front, inside the cloud, far away (both sides), behind.
  std::vector<P> ps = {{c, vec3(0, 1, 0)},
                       {c + vec3(0, 1e-6f, 0), vec3(0, -1, 0)},
                       {c + vec3(0.01f, 0.2f, 0.0f), vec3(0, -1, 0.1f)},
                       {vec3(0.5f), vec3(0.3f, 0.2f, 1.0f)},
                       {c + vec3(0, 1e4f, 0), vec3(0, -1, 0)},
                       {c - vec3(0, 1e-3f, 0), vec3(0, -1, 0)},
                       {c * 1e-3f, vec3(1, 0, 0)}};
  for (int glossy = 0; glossy < 2; ++glossy)
    for (const P& q : ps) {
      ShadingPoint sp;
      sp.p = q.p;
      sp.ng = glm::normalize(q.n);
      sp.basis = basis_from_normal(sp.ng);
      sp.wo = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
      sp.brdf = brdf_from_material(vec3(0.6f), glossy ? 0.5f : 0.0f, glossy ? 0.3f : 1.0f, !glossy);
      points.push_back(sp);
    }
  return points;
}

void PrintTo(const VplSetCase& c, std::ostream* os) { *os << c.name << " (" << c.vpls.size() << " VPLs)"; }

class ExtremesVplSet : public testing::TestWithParam<VplSetCase> {};

TEST_P(ExtremesVplSet, ExhaustiveAndUniformContributionsFinite) {
  const VplSet& vpls = GetParam().vpls;
  for (const ShadingPoint& sp : shading_points(vpls)) {
    vec3 sum(0.0f);
    for (const Vpl& v : vpls) {
      vec3 c = vpl_contribution(v, sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, kClamp);
      ASSERT_TRUE(is_finite(c));
      sum += c;
    }
    ASSERT_TRUE(is_finite(sum));
    // Uniform: one VPL / (1/N).
    ASSERT_TRUE(is_finite(divide_by_probability(vpl_contribution(vpls.back(), sp.p, sp.ng, sp.basis, sp.brdf, sp.wo,
                                                                 kClamp),
                                                tree_probability(float(1.0 / double(vpls.size()))))));
  }
}

TEST_P(ExtremesVplSet, SlcSamplesFinite) {
  const VplSet& vpls = GetParam().vpls;
  for (const char* builder : {"radix", "perfect", "agglomerative"}) {
    if (std::string(builder) == "agglomerative" && vpls.size() > 2000) continue;  // O(n^2)-ish builder
    SCOPED_TRACE(builder);
    LightTreeParams params;
    params.tree = builder;
    LightTree tree = build_light_tree(vpls, params);
    HashRng rng = hash_rng(3, 0, 0);
    for (const ShadingPoint& sp : shading_points(vpls))
      for (int s = 0; s < 16; ++s) {
        PixelSampler walk_ps = pixel_sampler(hash_rng_next_bits(rng), 0u, 0u);
        TreeWalk t = walk_tree(tree, slc_weights(sp), stop_at_leaves, walk_ps);
        if (t.node == kNoNode) continue;
        ASSERT_TRUE(tree[t.node].is_leaf());
        ASSERT_GT(probability_value(t.probability), 0.0);
        ASSERT_TRUE(std::isfinite(probability_value(t.probability)));
        vec3 c = vpl_contribution(vpls[tree[t.node].vpl()], sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, kClamp);
        ASSERT_TRUE(is_finite(divide_by_probability(c, t.probability)));
      }
  }
}

TEST_P(ExtremesVplSet, SstSamplesFinite) {
  const VplSet& vpls = GetParam().vpls;
  for (float v_min : {0.0f, 1.0f})
    for (float sigma_max : {0.0f, 1e6f})
      for (float eps : {0.0f, 0.1f}) {
        SCOPED_TRACE(testing::Message() << "v_min " << v_min << " sigma_max " << sigma_max << " eps " << eps);
        LightTreeParams params;
        params.v_min = v_min;
        params.sigma_max = sigma_max;
        LightTree tree = build_light_tree(vpls, params);
        HashRng rng = hash_rng(4, 0, 0);
        for (const ShadingPoint& sp0 : shading_points(vpls))
          for (int s = 0; s < 8; ++s) {
            ShadingPoint sp = sp0;
            SstLobe lobe = sp.brdf.specular ? SstLobe::glossy : SstLobe::diffuse;
            sp.brdf = sst_lobe_brdf(sp.brdf, lobe == SstLobe::glossy);
            PixelSampler walk_ps = pixel_sampler(hash_rng_next_bits(rng), 0u, 0u);
        TreeWalk t = walk_tree(tree, sst_weights(sp, eps, lobe), sst_stop_rule(lobe), walk_ps);
            if (t.node == kNoNode) continue;
            ASSERT_GT(probability_value(t.probability), 0.0);
            ASSERT_TRUE(std::isfinite(probability_value(t.probability)));
            const LightNode& node = tree[t.node];
            Vpl vpl;
            if (node.is_leaf()) {
              vpl = vpls[node.vpl()];
            } else {
              vec3 normals = sst_standard_normals(vec2(hash_rng_next(rng), hash_rng_next(rng)), vec2(hash_rng_next(rng), hash_rng_next(rng)));
              vpl = Vpl{sst_substitute_position(node, normals), node.normal, node.intensity};
              ASSERT_TRUE(is_finite(vpl.position));
              ASSERT_TRUE(is_finite(vpl.normal));
            }
            vec3 c = vpl_contribution(vpl, sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, kClamp);
            ASSERT_TRUE(is_finite(divide_by_probability(c, t.probability)));
          }
      }
}

TEST_P(ExtremesVplSet, RtslcCutsAndTraversalsFinite) {
  const VplSet& vpls = GetParam().vpls;
  LightTreeParams params;
  params.tree = "perfect";
  LightTree tree = build_light_tree(vpls, params);
  std::vector<uint32_t> cut;
  for (uint32_t m : {1u, 8u, 32u})
    for (const ShadingPoint& sp : shading_points(vpls)) {
      SCOPED_TRACE(testing::Message() << "cut_size " << m);
      vec3 x = sp.p, n = sp.ng;
      cut.clear();  // build_cut appends
      build_cut(tree, m, [&](const LightNode& node) { return rtslc_cut_error(node, x, n, kClamp); }, cut);
      ASSERT_FALSE(cut.empty());
      ASSERT_LE(cut.size(), size_t(m));
      for (uint32_t from : cut) {
        ASSERT_TRUE(std::isfinite(rtslc_cut_error(tree[from], x, n, kClamp)));
        for (uint32_t i = 0; i < 4; ++i) {
          PixelSampler sampler = pixel_sampler(11, from, i);
          RtslcSample s = rtslc_traverse(tree, from, x, n, sampler);
          if (s.node == kNoNode) continue;
          ASSERT_TRUE(tree[s.node].is_leaf());
          ASSERT_GT(s.probability, 0.0f);
          ASSERT_TRUE(std::isfinite(s.probability));
          vec3 c = vpl_contribution(vpls[tree[s.node].vpl()], sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, kClamp);
          ASSERT_TRUE(is_finite(divide_by_probability(c, tree_probability(s.probability))));
        }
      }
    }
}

TEST_P(ExtremesVplSet, HybridWeightsAndCutsFinite) {
  const VplSet& vpls = GetParam().vpls;
  LightTreeParams params;
  params.tree = "perfect";
  for (float v_min : {0.0f, 1.0f}) {
    params.v_min = v_min;
    LightTree tree = build_light_tree(vpls, params);
    std::vector<uint32_t> cut;
    for (uint32_t m : {1u, 32u})
      for (const ShadingPoint& sp : shading_points(vpls)) {
        vec3 x = sp.p, n = sp.ng;
        cut.clear();  // build_cut appends
        build_cut(tree, m, [&](const LightNode& node) { return hybrid_weight(node, x, n, kClamp, 0.0f); }, cut);
        ASSERT_FALSE(cut.empty());
        for (uint32_t node : cut) {
          float w = hybrid_weight(tree[node], x, n, kClamp, 0.0f);
          ASSERT_TRUE(std::isfinite(w));
          ASSERT_GE(w, 0.0f);
        }
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Sets, ExtremesVplSet, testing::ValuesIn(vpl_set_cases()),
                         [](const testing::TestParamInfo<VplSetCase>& info) { return info.param.name; });

}  // namespace
}  // namespace sst
