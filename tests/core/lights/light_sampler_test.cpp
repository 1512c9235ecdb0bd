// The light samplers (core/lights/light_sampler.h, emitter_tree.h, emitter_tree_build.h) in the
// manner of pbrt-v4's light-sampler tests: for random shading points the pmf each sampler reports
// for every light sums to 1 and matches the frequency with which the sampler picks it
// (chi-square, fixed seeds); a light gets probability 0 only where it provably sends nothing to
// the point; the tree's nodes bound their children; a pick's pmf equals the pmf asked for it.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "core/lights/emitter_tree_build.h"
#include "core/lights/light_sampler.h"
#include "core/util/error.h"
#include "tests/analytic_scenes.h"
#include "tests/stat_util.h"

namespace sst {
namespace {

constexpr LightSamplerKind kAllKinds[] = {LightSamplerKind::Uniform, LightSamplerKind::Power, LightSamplerKind::Tree,
                                          LightSamplerKind::Slc};

float uniform01(std::mt19937& rng) { return float(rng() >> 8) * 0x1p-24f; }

vec3 random_direction(std::mt19937& rng) {
  float z = 2.0f * uniform01(rng) - 1.0f, phi = 6.2831853f * uniform01(rng);
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return vec3(r * std::cos(phi), z, r * std::sin(phi));
}

// Shading points: on the floor and ceiling (normal toward the room), and in the air with a random
// normal (where lights behind the normal's plane must get nothing).
struct ShadingPoint {
  vec3 p, n;
};
std::vector<ShadingPoint> shading_points(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::vector<ShadingPoint> points;
  for (int i = 0; i < count; ++i) {
    vec3 p(8.0f * uniform01(rng) - 4.0f, 0.0f, 8.0f * uniform01(rng) - 4.0f);
    vec3 n(0.0f, 1.0f, 0.0f);
    if (i % 3 == 1) p.y = 4.0f, n = vec3(0.0f, -1.0f, 0.0f);
    if (i % 3 == 2) p.y = 0.2f + 3.6f * uniform01(rng), n = random_direction(rng);
    points.push_back({p, n});
  }
  return points;
}

// Both builds: every inner node bounds its children, each child names it as its parent, the
// nodes 1 .. 2 leaves - 1 form one tree (each reached once from the root), and every light has a
// leaf that names it back.
TEST(EmitterTree, InnerNodesBoundTheirChildren) {
  Scene scene = test::many_lights(1, 3000, 40, 40, true);
  for (EmitterTreeBuild build : {EmitterTreeBuild::Saoh, EmitterTreeBuild::Morton}) {
    SCOPED_TRACE(emitter_tree_build_name(build));
    LightSampler lights(scene, LightSamplerKind::Tree, build);
    const PackedLights& packed = lights.packed();
    const uint32_t leaves = packed.header.tree_leaves;
    // 3000-odd triangles and 80 punctual lights; morton pads them to a power of two.
    if (build == EmitterTreeBuild::Morton) ASSERT_EQ(leaves, 4096u);
    else ASSERT_EQ(leaves, uint32_t(lights.light_count() - 1));  // all but the sun
    ASSERT_EQ(packed.header.directional_count, 1u);
    ASSERT_EQ(packed.tree.size(), 2u * leaves + 1u);
    auto angle = [](vec3 a, vec3 b) { return std::atan2(double(glm::length(glm::cross(a, b))), double(glm::dot(a, b))); };
    int checked = 0;
    std::vector<int> reached(2 * leaves, 0);
    std::vector<std::pair<uint32_t, uint32_t>> stack{{1u, 0u}};  // node, depth
    uint32_t deepest = 0;
    while (!stack.empty()) {
      auto [i, depth] = stack.back();
      stack.pop_back();
      ASSERT_LT(i, 2 * leaves);
      ++reached[i];
      deepest = std::max(deepest, depth);
      const EmitterNode& parent = packed.tree[i];
      if (parent.children == 0u) continue;
      double sum = 0.0;
      for (uint32_t c : {parent.children, parent.children + 1}) {
        const EmitterNode& child = packed.tree[c];
        EXPECT_EQ(child.parent, i) << c;
        stack.push_back({c, depth + 1});
        if (!(child.intensity > 0.0f)) continue;
        sum += child.intensity;
        EXPECT_TRUE(glm::all(glm::lessThanEqual(parent.lo, child.lo)) && glm::all(glm::greaterThanEqual(parent.hi, child.hi)))
            << i;
        // The child's cone lies in the parent's: angle between axes + child's half angle <= parent's;
        // a two-sided parent may hold the child's cone turned about. The child's half angle is the
        // least its float cosine can stand for: the build unites cones at their exact angles and
        // stores each cosine rounded down, and near 0 one float step of a cosine is many times
        // the parent's 1e-6 of slack (a clang build failed here by 1e-6 with the stored angle).
        if (parent.cos_o > -1.0f) {
          const float cos_child = child.cos_o >= 1.0f ? 1.0f : std::nextafter(child.cos_o, 2.0f);
          double theta_child = std::acos(std::clamp(double(cos_child), -1.0, 1.0));
          double theta_parent = std::acos(std::clamp(double(parent.cos_o), -1.0, 1.0));
          double between = angle(parent.axis, child.axis);
          if (parent.flags & EMITTER_TWO_SIDED) between = std::min(between, angle(parent.axis, -child.axis));
          EXPECT_LE(between + theta_child, theta_parent + 1e-6) << i;
        }
        EXPECT_LE(parent.cos_e, child.cos_e) << i;
        if (child.flags & EMITTER_TWO_SIDED) EXPECT_TRUE(parent.flags & EMITTER_TWO_SIDED) << i;
        ++checked;
      }
      EXPECT_NEAR(parent.intensity, sum, 1e-5 * sum) << i;
    }
    for (uint32_t i = 1; i < 2 * leaves; ++i) EXPECT_EQ(reached[i], 1) << i;
    EXPECT_LE(deepest, kEmitterTreeMaxDepth);
    EXPECT_GT(checked, 6000);
    for (uint32_t e = 0; e < lights.light_count(); ++e) {
      uint32_t node = packed.distribution[e].tree_node;
      ASSERT_NE(node, LIGHT_NONE) << e;
      EXPECT_EQ(packed.tree[node].entry, e);
      EXPECT_EQ(packed.tree[node].children, 0u);
    }
  }
}

// Ranges longer than a chunk are binned in parallel: the tree must not depend on the threads.
TEST(EmitterTree, TheSaohBuildIsTheSameOnAnyThreadCount) {
  Scene scene = test::many_lights(8, 40000, 20, 20, false);
  auto build = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    return LightSampler(scene, LightSamplerKind::Tree).packed().tree;
  };
  const EmitterNodes one = build(1), two = build(2), four = build(4);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), four.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(EmitterNode)), 0);
  EXPECT_EQ(std::memcmp(one.data(), four.data(), one.size() * sizeof(EmitterNode)), 0);
}

TEST(EmitterTree, ConeUnionHoldsBothCones) {
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    EmitterNode a{}, b{};
    a.intensity = b.intensity = 1.0f;
    a.axis = random_direction(rng);
    b.axis = i % 4 == 0 ? -a.axis : random_direction(rng);
    a.cos_o = std::cos(3.1415926f * uniform01(rng) * (i % 3 == 0 ? 0.0f : 1.0f));
    b.cos_o = std::cos(3.1415926f * uniform01(rng) * 0.5f);
    a.cos_e = b.cos_e = 0.0f;
    EmitterNode m = merge_emitter_nodes(a, b);
    for (const EmitterNode& c : {a, b}) {
      // Directions on the rim of the child's cone lie within the merged cone.
      for (int k = 0; k < 16; ++k) {
        vec3 t = glm::normalize(glm::cross(c.axis, random_direction(rng)));
        float theta = std::acos(std::clamp(c.cos_o, -1.0f, 1.0f));
        vec3 w = std::cos(theta) * c.axis + std::sin(theta) * t;
        EXPECT_GE(glm::dot(w, m.axis), m.cos_o - 2e-6f) << i;
      }
    }
  }
}

// The contribution a light can send to (p, n), provably zero or not, for the zero-pmf check:
// points of an emissive triangle (its vertices and interior samples) in front of n and, for a
// one-sided emitter, behind its front; a spot's cone; anything in front of n for a point light;
// a directional light from above n's plane.
bool can_contribute(const Scene& scene, const LightSampler& lights, uint32_t entry, vec3 p, vec3 n, std::mt19937& rng) {
  const size_t punctual = scene.lights.size();
  if (entry < punctual) {
    const PunctualLight& l = scene.lights[entry];
    if (l.type == LightType::Directional) return glm::dot(n, -l.direction) > 0.0f;
    vec3 d = l.position - p;
    if (!(glm::dot(n, d) > 0.0f)) return false;
    if (l.type == LightType::Spot) return glm::dot(l.direction, -glm::normalize(d)) > l.cos_outer;
    return true;
  }
  uint32_t tri = lights.packed().emissive[entry - punctual].triangle;
  vec3 v[3];
  light_triangle_vertices(scene, tri, v[0], v[1], v[2]);
  vec3 ng = triangle_geometric_normal(scene, tri);
  bool two_sided = scene.materials[scene.triangle_material[tri]].double_sided;
  for (int k = 0; k < 67; ++k) {
    vec3 y = k < 3 ? v[k] : [&] {
      vec2 b = sample_uniform_triangle(uniform01(rng), uniform01(rng));
      return (1.0f - b.x - b.y) * v[0] + b.x * v[1] + b.y * v[2];
    }();
    vec3 d = y - p;
    if (glm::dot(n, d) > 0.0f && (two_sided || glm::dot(ng, -d) > 0.0f)) return true;
  }
  return false;
}

// For every sampler: pick frequencies against pmfs (chi-square at 1e-6), the pick's pmf against
// light_pick_pmf, and zero pmfs only for lights that cannot contribute. The tree samplers may
// reach an inner node whose bound is positive while both children's are zero: every light below
// it sends nothing to the point, and the pick returns no light. Such dead ends are a bin of their
// own, of probability 1 - sum of the pmfs; the pmfs with it sum to 1.
void check_sampler(const Scene& scene, LightSamplerKind kind, uint32_t seed, int points, int picks,
                   bool expect_culled = false, EmitterTreeBuild build = EmitterTreeBuild::Saoh) {
  SCOPED_TRACE(light_sampler_name(kind));
  SCOPED_TRACE(emitter_tree_build_name(build));
  LightSampler lights(scene, kind, build);
  const uint32_t count = uint32_t(lights.light_count());
  std::mt19937 rng(seed);
  int zero_checked = 0, failures = 0;
  double dead_end_mass = 0.0;
  for (const ShadingPoint& sp : shading_points(seed, points)) {
    std::vector<double> expected(count + 1, 0.0), observed(count + 1, 0.0);  // the last bin: no light
    double total = 0.0;
    for (uint32_t e = 0; e < count; ++e) total += expected[e] = lights.pmf(sp.p, sp.n, e);
    if (total == 0.0) {
      float pmf = 0.0f, u = 0.0f;
      EXPECT_EQ(lights.pick(sp.p, sp.n, 0.5f, pmf, u), LIGHT_NONE);
      continue;
    }
    if (kind == LightSamplerKind::Uniform || kind == LightSamplerKind::Power) EXPECT_NEAR(total, 1.0, 2e-5);
    EXPECT_LE(total, 1.0 + 2e-5);
    dead_end_mass = std::max(dead_end_mass, 1.0 - total);
    expected[count] = std::max(0.0, 1.0 - total);
    for (int k = 0; k < picks; ++k) {
      float pmf = 0.0f, u_remapped = 0.0f;
      uint32_t e = lights.pick(sp.p, sp.n, uniform01(rng), pmf, u_remapped);
      if (e == LIGHT_NONE) {
        observed[count] += 1.0;
        continue;
      }
      ASSERT_LT(e, count);
      if (pmf != float(expected[e]) && failures++ < 5) ADD_FAILURE() << "pick's pmf " << pmf << " != pmf " << expected[e];
      EXPECT_TRUE(u_remapped >= 0.0f && u_remapped < 1.0f);
      observed[e] += 1.0;
    }
    for (double& x : expected) x *= double(picks);
    int dof = 0;
    double chi2 = test::chi_square_statistic(observed, expected, &dof);
    EXPECT_LT(chi2, test::chi_square_critical_1e6(dof)) << "point " << sp.p.x << "," << sp.p.y << "," << sp.p.z;
    for (uint32_t e = 0; e < count; ++e) {
      if (expected[e] > 0.0) continue;
      ++zero_checked;
      EXPECT_FALSE(can_contribute(scene, lights, e, sp.p, sp.n, rng)) << "light " << e << " has pmf 0";
    }
  }
  if (expect_culled && kind == LightSamplerKind::Tree) EXPECT_GT(zero_checked, 100);  // the test saw culled lights
  std::printf("%s: %d points, lights of pmf 0 checked %d, largest dead-end mass %.4f\n", light_sampler_name(kind),
              points, zero_checked, dead_end_mass);
}

TEST(LightSamplers, PmfsSumToOneAndMatchPickFrequencies) {
  Scene scene = test::many_lights(2, 300, 10, 12, true);
  for (LightSamplerKind kind : kAllKinds) check_sampler(scene, kind, 11, 24, 60000, true);
  for (LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Slc})
    check_sampler(scene, kind, 11, 24, 60000, true, EmitterTreeBuild::Morton);
}

TEST(LightSamplers, ManyLightsWithoutDirectionalOrPunctual) {
  Scene scene = test::many_lights(3, 2000, 0, 0, false);
  for (EmitterTreeBuild build : {EmitterTreeBuild::Saoh, EmitterTreeBuild::Morton})
    for (LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Slc})
      check_sampler(scene, kind, 12, 6, 200000, true, build);
}

// Point lights in a row, each half again as far along it as the last and twice as bright: the
// heuristic's cheapest split sets the farthest light apart at every level, a tree as deep as the
// row is long. The build halves what remains once the depth nears kEmitterTreeMaxDepth, so every
// leaf's path fits the pmf's 64-bit trail, and the pmfs (read through both halves of the
// trail) still match the picks.
TEST(LightSamplers, TheDepthStaysWithinTheTrail) {
  Scene scene = test::many_lights(15, 0, 0, 0, false);
  for (int i = 0; i < 120; ++i) {
    PunctualLight l;
    l.type = LightType::Point;
    l.position = vec3(-3.0f + 1e-6f * std::pow(1.5f, float(i)), 2.0f, 0.0f);
    l.intensity = vec3(std::ldexp(1.0f, i - 60));
    scene.lights.push_back(l);
  }
  LightSampler lights(scene, LightSamplerKind::Tree);
  const PackedLights& packed = lights.packed();
  uint32_t deepest = 0;
  for (uint32_t e = 0; e < lights.light_count(); ++e) {
    uint32_t depth = 0;
    for (uint32_t node = packed.distribution[e].tree_node; node != 1u; node = packed.tree[node].parent) ++depth;
    deepest = std::max(deepest, depth);
  }
  EXPECT_EQ(deepest, kEmitterTreeMaxDepth);  // the heuristic went as deep as the trail allows
  check_sampler(scene, LightSamplerKind::Tree, 16, 12, 40000);
}

TEST(LightSamplers, OnlyPunctualLights) {
  Scene scene = test::many_lights(4, 0, 7, 9, true);
  for (LightSamplerKind kind : kAllKinds) check_sampler(scene, kind, 13, 30, 20000);
}

TEST(LightSamplers, OneLightTakesEveryPick) {
  Scene scene = test::many_lights(5, 1, 0, 0, false);
  ASSERT_EQ(LightSampler(scene).light_count(), 1u);
  for (LightSamplerKind kind : kAllKinds) check_sampler(scene, kind, 14, 9, 100);
}

// A sample's pdf is the pick's pmf times the point's density, and the MIS pdf of hitting the same
// point on an emissive triangle by BSDF sampling is the same number.
TEST(LightSamplers, SamplePdfEqualsEmissiveHitPdf) {
  Scene scene = test::many_lights(6, 500, 5, 5, true);
  for (LightSamplerKind kind : kAllKinds) {
    SCOPED_TRACE(light_sampler_name(kind));
    LightSampler lights(scene, kind);
    std::mt19937 rng(21);
    int compared = 0;
    for (const ShadingPoint& sp : shading_points(22, 200)) {
      LightSample s;
      vec2 u(uniform01(rng), uniform01(rng));
      if (!lights.sample(sp.p, sp.n, u, s) || s.delta) continue;
      // The triangle the point lies on: the one the pick chose.
      float pmf = 0.0f, u1 = 0.0f;
      uint32_t e = lights.pick(sp.p, sp.n, u.x, pmf, u1);
      uint32_t tri = lights.packed().emissive[e - scene.lights.size()].triangle;
      float hit = lights.pdf_emissive_hit(sp.p, sp.n, tri, s.point, s.normal);
      // Solid-angle samples report the density of their warp, the hit its solid angle: the two
      // agree to float error of the spherical-triangle formulas (measured: 2e-4).
      EXPECT_NEAR(hit, s.pdf, 1e-3f * s.pdf);
      ++compared;
    }
    EXPECT_GT(compared, 50);
  }
}

TEST(LightSamplers, NamesRoundTrip) {
  for (LightSamplerKind kind : kAllKinds) EXPECT_EQ(parse_light_sampler(light_sampler_name(kind)), kind);
  EXPECT_THROW(parse_light_sampler("bvh"), Error);
  for (EmitterTreeBuild build : {EmitterTreeBuild::Saoh, EmitterTreeBuild::Morton})
    EXPECT_EQ(parse_emitter_tree_build(emitter_tree_build_name(build)), build);
  EXPECT_THROW(parse_emitter_tree_build("bvh"), Error);
}

}  // namespace
}  // namespace sst
