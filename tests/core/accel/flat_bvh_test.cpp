// The GPU backend's BVH (core/accel/flat_bvh, core/accel/bvh_*.h): the flattened tree's
// invariants, and the shared traversal (the code the shaders run, compiled as C++) against
// Embree: closest hits, occlusion, watertightness at shared edges and vertices, and that the
// GLSL side still compiles.
#include "core/accel/flat_bvh.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "tests/test_util.h"

namespace sst {
namespace {

struct Rng {
  std::mt19937 engine;
  explicit Rng(uint32_t seed) : engine(seed) {}
  float uniform() { return float(engine() >> 8) * (1.0f / 16777216.0f); }
  float uniform(float a, float b) { return a + (b - a) * uniform(); }
  vec3 in_box(const Bounds3& b) {
    return {uniform(b.lo.x, b.hi.x), uniform(b.lo.y, b.hi.y), uniform(b.lo.z, b.hi.z)};
  }
  vec3 direction() {
    float z = uniform(-1.0f, 1.0f), phi = uniform(0.0f, 2.0f * kPi);
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
};

const Scene& cornell_box() {
  static const Scene scene = load_default_scene();
  return scene;
}

// The staircase of the shared scenes, loaded once; nullptr when absent.
const Scene* staircase() {
  static const Scene* scene = [] () -> const Scene* {
    auto path = test::shared_scene("staircase/staircase.gltf");
    if (path.empty()) return nullptr;
    return new Scene(load_gltf(path.string()));
  }();
  return scene;
}

bool is_leaf(const glsl::BvhNode& n) { return (n.count_and_flags & BVH_LEAF_FLAG) != 0u; }
uint32_t leaf_count(const glsl::BvhNode& n) { return n.count_and_flags & BVH_COUNT_MASK; }
bool inside(vec3 p, vec3 lo, vec3 hi) { return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi)); }

void check_invariants(const Scene& scene, const FlatBvh& bvh, bool spatial_splits) {
  ASSERT_FALSE(bvh.nodes.empty());
  EXPECT_EQ(bvh.stats.node_count, bvh.nodes.size());
  EXPECT_EQ(bvh.stats.triangle_refs, bvh.triangles.size());
  EXPECT_LE(bvh.stats.max_depth, uint32_t(BVH_STACK_SIZE));

  std::vector<uint32_t> references(scene.triangles.size(), 0);
  std::vector<uint32_t> visits(bvh.nodes.size(), 0);
  uint32_t next_triangle = 0, leaves = 0, max_depth = 0, max_leaf = 0;
  int failures = 0;
  // Depth-first walk in layout order: (node, depth).
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 0u}};
  while (!stack.empty() && failures < 20) {
    auto [i, depth] = stack.back();
    stack.pop_back();
    ASSERT_LT(i, bvh.nodes.size());
    ++visits[i];
    const glsl::BvhNode& n = bvh.nodes[i];
    max_depth = std::max(max_depth, depth);
    if (is_leaf(n)) {
      ++leaves;
      max_leaf = std::max(max_leaf, leaf_count(n));
      // Leaves own consecutive ranges, in depth-first order.
      EXPECT_EQ(n.first_or_right, next_triangle) << "leaf " << i;
      next_triangle = n.first_or_right + leaf_count(n);
      ASSERT_LE(next_triangle, bvh.triangles.size());
      for (uint32_t k = n.first_or_right; k < next_triangle; ++k) {
        const glsl::BvhTriangle& t = bvh.triangles[k];
        ASSERT_LT(t.triangle, scene.triangles.size());
        ++references[t.triangle];
        const uvec3 tri = scene.triangles[t.triangle];
        EXPECT_EQ(t.v0, scene.positions[tri.x]);
        EXPECT_EQ(t.v1, scene.positions[tri.y]);
        EXPECT_EQ(t.v2, scene.positions[tri.z]);
        EXPECT_EQ(t.flags, 0u);  // no material of this scene has an alpha test
        EXPECT_EQ(t.reserved, 0u);
        // Without spatial splits a leaf's box holds its whole triangles.
        if (!spatial_splits)
          for (vec3 v : {t.v0, t.v1, t.v2})
            if (!inside(v, n.bounds_min, n.bounds_max) && ++failures < 5)
              ADD_FAILURE() << "triangle " << t.triangle << " outside leaf " << i;
      }
      continue;
    }
    const uint32_t left = i + 1, right = n.first_or_right;
    EXPECT_LE(n.count_and_flags, 2u) << "inner node " << i << " flags";
    ASSERT_LT(left, bvh.nodes.size());
    ASSERT_LT(right, bvh.nodes.size());
    ASSERT_GT(right, left);
    for (uint32_t c : {left, right}) {
      const glsl::BvhNode& child = bvh.nodes[c];
      if (!(inside(child.bounds_min, n.bounds_min, n.bounds_max) && inside(child.bounds_max, n.bounds_min, n.bounds_max)) &&
          ++failures < 5)
        ADD_FAILURE() << "child " << c << " not inside parent " << i;
    }
    stack.push_back({right, depth + 1});
    stack.push_back({left, depth + 1});
  }
  EXPECT_LT(failures, 1);
  EXPECT_EQ(next_triangle, bvh.triangles.size());
  EXPECT_EQ(leaves, bvh.stats.leaf_count);
  EXPECT_EQ(max_depth, bvh.stats.max_depth);
  EXPECT_EQ(max_leaf, bvh.stats.max_leaf_size);
  for (size_t i = 0; i < visits.size(); ++i)
    if (visits[i] != 1u) {
      ADD_FAILURE() << "node " << i << " reached " << visits[i] << " times";
      break;
    }
  for (size_t t = 0; t < references.size(); ++t) {
    const bool ok = spatial_splits ? references[t] >= 1u : references[t] == 1u;
    if (!ok) {
      ADD_FAILURE() << "triangle " << t << " is in " << references[t] << " leaves";
      break;
    }
  }
}

// Closest-hit agreement. Differing triangles are a tie (coincident surfaces, a ray through a
// shared edge) only when t agrees.
struct Agreement {
  int rays = 0, hits = 0, ties = 0, embree_leaks = 0, failures = 0;
};

bool same_t(float a, float b) { return std::abs(a - b) <= 1e-5f * std::max(1.0f, std::max(std::abs(a), std::abs(b))) ; }

void compare_ray(const Scene& scene, const FlatBvh& bvh, const EmbreeAccel& accel, const Ray& ray, Agreement& a,
                 bool allow_embree_leak = false) {
  ++a.rays;
  const Hit e = accel.intersect(ray);
  const FlatHit f = flat_bvh_intersect(bvh, ray.origin, ray.direction, ray.tmin, ray.tmax);
  auto fail = [&](const char* what) {
    if (++a.failures <= 5)
      ADD_FAILURE() << what << ": origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir ("
                    << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z << ") tmin " << ray.tmin
                    << " tmax " << ray.tmax << ": embree tri " << e.triangle << " t " << e.t << ", flat tri "
                    << f.triangle << " t " << f.t;
  };
  if (!f.valid()) {
    EXPECT_EQ(f.t, kInf);
    if (e.valid()) fail("flat BVH misses");
    return;
  }
  if (!e.valid()) {
    // Embree (not RTC_SCENE_FLAG_ROBUST) is not watertight: it may leak through an edge that the
    // rays aimed at edges and vertices hit exactly.
    if (allow_embree_leak) ++a.embree_leaks;
    else fail("flat BVH hits where Embree misses");
    return;
  }
  ++a.hits;
  if (allow_embree_leak && f.t < e.t && f.t <= 1.0f + 1e-4f && !same_t(e.t, f.t)) {
    ++a.embree_leaks;  // Embree slipped through the edge aimed at (t = 1) and hit something behind
    return;
  }
  if (e.triangle != f.triangle) {
    if (!same_t(e.t, f.t)) return fail("t differs");
    ++a.ties;
    return;
  }
  if (!same_t(e.t, f.t)) {
    // Grazing or degenerate triangles: t is then good to eps * magnitude / cos only, in either
    // intersector; the flat BVH's must be no worse than Embree's against a double computation.
    const uvec3 tri = scene.triangles[f.triangle];
    const dvec3 p0 = scene.positions[tri.x];
    const dvec3 n = glm::cross(dvec3(scene.positions[tri.y]) - p0, dvec3(scene.positions[tri.z]) - p0);
    const dvec3 d = ray.direction;
    const double exact = glm::dot(p0 - dvec3(ray.origin), n) / glm::dot(d, n);
    const double cos_theta = std::abs(glm::dot(glm::normalize(d), glm::normalize(n)));
    const double scale = glm::length(dvec3(ray.origin)) + glm::length(p0) + exact * glm::length(d);
    const double tolerance = std::max({1e-5 * exact, 2.0 * std::abs(e.t - exact),
                                       16.0 * 0x1p-24 * scale / (std::max(cos_theta, 1e-30) * glm::length(d))});
    if (std::abs(f.t - exact) > tolerance) return fail("t differs");
  }
  if (std::abs(e.barycentric.x - f.barycentric.x) <= 1e-4f && std::abs(e.barycentric.y - f.barycentric.y) <= 1e-4f) return;
  // Slivers (the staircase has 6 m x 2 mm triangles): both intersectors lose digits of u, v in
  // float; the flat BVH's must then be no worse than Embree's, against a double computation.
  const uvec3 tri = scene.triangles[f.triangle];
  const dvec3 p0 = scene.positions[tri.x], e1 = dvec3(scene.positions[tri.y]) - p0, e2 = dvec3(scene.positions[tri.z]) - p0;
  const dvec3 d = ray.direction, tv = dvec3(ray.origin) - p0, pv = glm::cross(d, e2), qv = glm::cross(tv, e1);
  const double det = glm::dot(e1, pv);
  const glm::dvec2 exact(glm::dot(tv, pv) / det, glm::dot(d, qv) / det);
  const double err_flat = glm::length(glm::dvec2(f.barycentric) - exact);
  const double err_embree = glm::length(glm::dvec2(e.barycentric) - exact);
  // Float barycentrics are good to about eps * (coordinate magnitude) / (smallest triangle height).
  const double area2 = glm::length(glm::cross(e1, e2));
  const double longest = std::max({glm::length(e1), glm::length(e2), glm::length(e2 - e1)});
  const double scale = glm::length(dvec3(ray.origin)) + f.t * glm::length(d) + glm::length(p0);
  const double conditioning = 16.0 * 0x1p-24 * scale / std::max(area2 / longest, 1e-30);
  if (err_flat > std::max({1e-4, 2.0 * err_embree, conditioning})) fail("barycentrics less accurate than Embree's");
}

std::vector<Ray> random_rays(const Scene& scene, uint32_t seed, int count) {
  Rng rng(seed);
  std::vector<Ray> rays;
  const Bounds3 box = scene.bounds;
  const float diag = box.diagonal();
  for (int i = 0; i < count; ++i) {
    Ray r;
    switch (i % 5) {
      case 0:  // from inside the box, unit direction
        r.origin = rng.in_box(box);
        r.direction = rng.direction();
        break;
      case 1: {  // from outside, aimed at a point inside
        r.origin = box.center() + 1.5f * diag * rng.direction();
        r.direction = rng.in_box(box) - r.origin;
        break;
      }
      case 2:  // not unit length, a finite interval
        r.origin = rng.in_box(box);
        r.direction = rng.direction() * rng.uniform(0.05f, 20.0f);
        r.tmin = rng.uniform(0.0f, 0.2f) * diag / glm::length(r.direction);
        r.tmax = r.tmin + rng.uniform(0.0f, 1.0f) * diag / glm::length(r.direction);
        break;
      case 3: {  // axis-aligned and diagonal directions: zero components
        static const vec3 dirs[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                                    {1, 1, 0}, {0, -1, 1}, {-1, 0, -1}, {1, 1, 1}};
        r.origin = rng.in_box(box);
        r.direction = dirs[rng.engine() % 10];
        break;
      }
      default: {  // from a point on a surface, off it by the accel's epsilon
        const uvec3 t = scene.triangles[rng.engine() % scene.triangles.size()];
        float u = rng.uniform(), v = rng.uniform();
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        vec3 p0 = scene.positions[t.x], p1 = scene.positions[t.y], p2 = scene.positions[t.z];
        vec3 p = (1.0f - u - v) * p0 + u * p1 + v * p2;
        vec3 ng = glm::cross(p1 - p0, p2 - p0);
        float len = glm::length(ng);
        ng = len > 0.0f ? ng / len : vec3(0, 0, 1);
        vec3 d = rng.direction();
        if (glm::dot(d, ng) < 0.0f) ng = -ng;
        r.origin = p + ng * (1e-5f * diag + 1e-6f * max_component(glm::abs(p)));
        r.direction = d;
        break;
      }
    }
    rays.push_back(r);
  }
  return rays;
}

// Rays aimed at points of edges shared by two coplanar triangles and at shared vertices, from
// random points of the scene's box: each must hit (its target or something before it).
struct EdgeRays {
  std::vector<Ray> rays;
  std::vector<bool> at_vertex;
};

EdgeRays edge_and_vertex_rays(const Scene& scene, uint32_t seed, size_t max_targets) {
  using Key = std::tuple<float, float, float>;
  auto key = [](vec3 p) { return Key{p.x, p.y, p.z}; };
  auto normal = [&](uint32_t t) {
    const uvec3 tri = scene.triangles[t];
    vec3 n = glm::cross(scene.positions[tri.y] - scene.positions[tri.x], scene.positions[tri.z] - scene.positions[tri.x]);
    float len = glm::length(n);
    return len > 0.0f ? n / len : vec3(0.0f);
  };
  std::map<std::pair<Key, Key>, std::vector<uint32_t>> edges;
  std::map<Key, std::vector<uint32_t>> vertices;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const uvec3 tri = scene.triangles[t];
    const vec3 p[3] = {scene.positions[tri.x], scene.positions[tri.y], scene.positions[tri.z]};
    for (int i = 0; i < 3; ++i) {
      Key a = key(p[i]), b = key(p[(i + 1) % 3]);
      edges[a < b ? std::pair{a, b} : std::pair{b, a}].push_back(t);
      vertices[a].push_back(t);
    }
  }
  Rng rng(seed);
  EdgeRays out;
  const Bounds3 box = scene.bounds;
  auto add = [&](vec3 target, const std::vector<uint32_t>& tris, bool vertex) {
    for (int attempt = 0; attempt < 8; ++attempt) {
      Ray r;
      r.origin = rng.in_box(box);
      r.direction = target - r.origin;
      const float len = glm::length(r.direction);
      if (len < 1e-3f * box.diagonal()) continue;
      // Not grazing: the ray crosses the plane of the triangles it aims between.
      bool steep = true;
      for (uint32_t t : tris) steep = steep && std::abs(glm::dot(r.direction / len, normal(t))) > 0.05f;
      if (!steep) continue;
      out.rays.push_back(r);
      out.at_vertex.push_back(vertex);
      return;
    }
  };
  size_t targets = 0;
  for (const auto& [edge, tris] : edges) {
    if (tris.size() != 2 || std::abs(glm::dot(normal(tris[0]), normal(tris[1]))) < 0.9999f) continue;
    const vec3 a(std::get<0>(edge.first), std::get<1>(edge.first), std::get<2>(edge.first));
    const vec3 b(std::get<0>(edge.second), std::get<1>(edge.second), std::get<2>(edge.second));
    for (float s : {0.5f, rng.uniform(), rng.uniform()}) add(glm::mix(a, b, s), tris, false);
    if (++targets >= max_targets) break;
  }
  // Vertices inside a flat region: a closed fan of coplanar triangles (every edge at the vertex
  // shared by exactly two of them). A ray may legitimately pass beside any other vertex.
  targets = 0;
  for (const auto& [v, tris] : vertices) {
    if (tris.size() < 3) continue;
    bool flat = true;
    std::map<Key, int> edge_uses;
    for (uint32_t t : tris) {
      flat = flat && std::abs(glm::dot(normal(t), normal(tris[0]))) >= 0.9999f;
      const uvec3 tri = scene.triangles[t];
      for (uint32_t i : {tri.x, tri.y, tri.z})
        if (key(scene.positions[i]) != v) ++edge_uses[key(scene.positions[i])];
    }
    for (const auto& [other, uses] : edge_uses) flat = flat && uses == 2;
    if (!flat) continue;
    add(vec3(std::get<0>(v), std::get<1>(v), std::get<2>(v)), tris, true);
    if (++targets >= max_targets) break;
  }
  return out;
}

void check_against_embree(const Scene& scene, const FlatBvh& bvh, int ray_count, const char* name) {
  EmbreeAccel accel(scene);
  Agreement a;
  for (const Ray& r : random_rays(scene, 1234u, ray_count)) compare_ray(scene, bvh, accel, r, a);
  EXPECT_EQ(a.failures, 0);
  EXPECT_GT(a.hits, a.rays / 4);
  // Ties are coincident surfaces (the Cornell box's blocks have bottoms on the floor) or rays
  // through an edge; t agrees, which is checked, only the pick between equals may differ.
  EXPECT_LE(a.ties, a.rays / 50 + 1);
  std::printf("[%s] random rays: %d, hits %d, ties %d\n", name, a.rays, a.hits, a.ties);

  // Watertightness: every ray aimed at a shared edge or vertex hits no later than its target.
  EdgeRays edge_rays = edge_and_vertex_rays(scene, 99u, 4000);
  ASSERT_GT(edge_rays.rays.size(), 10u);
  int vertex_rays = 0;
  for (bool v : edge_rays.at_vertex) vertex_rays += v;
  Agreement b;
  int leaks = 0;
  for (size_t i = 0; i < edge_rays.rays.size(); ++i) {
    const Ray& r = edge_rays.rays[i];
    const FlatHit f = flat_bvh_intersect(bvh, r.origin, r.direction, r.tmin, r.tmax);
    if (!(f.valid() && f.t <= 1.0f + 1e-4f)) {
      if (++leaks <= 5)
        ADD_FAILURE() << "ray through a shared " << (edge_rays.at_vertex[i] ? "vertex" : "edge") << " leaks: origin ("
                      << r.origin.x << ", " << r.origin.y << ", " << r.origin.z << ") target ("
                      << (r.origin + r.direction).x << ", " << (r.origin + r.direction).y << ", "
                      << (r.origin + r.direction).z << "), t " << f.t;
    }
    compare_ray(scene, bvh, accel, r, b, /*allow_embree_leak=*/true);
  }
  EXPECT_EQ(leaks, 0);
  EXPECT_EQ(b.failures, 0);
  std::printf("[%s] rays at shared edges/vertices: %d (%d at vertices), flat BVH leaks %d, Embree leaks %d, ties %d\n",
              name, b.rays, vertex_rays, leaks, b.embree_leaks, b.ties);
}

void check_occlusion(const Scene& scene, const FlatBvh& bvh, int ray_count, const char* name) {
  EmbreeAccel accel(scene);
  Rng rng(777u);
  int checked = 0, occluded = 0, mismatches = 0, embree_leaks = 0;
  auto check = [&](const Ray& r) {
    const Hit closest = accel.intersect(Ray{r.origin, r.direction, r.tmin, kInf});
    // The interval's end at a surface is ambiguous to float precision: skip those.
    if (closest.valid() && same_t(closest.t, r.tmax)) return;
    ++checked;
    const bool e = accel.occluded(r);
    const bool f = flat_bvh_occluded(bvh, r.origin, r.direction, r.tmin, r.tmax);
    occluded += e;
    // Embree is not watertight: a ray through an edge shared by two triangles may pass between
    // them, where the flat BVH's watertight test hits one (counted, as compare_ray counts them).
    if (f && !e) {
      const FlatHit h = flat_bvh_intersect(bvh, r.origin, r.direction, r.tmin, r.tmax);
      const float edge = std::min(std::min(h.barycentric.x, h.barycentric.y), 1.0f - h.barycentric.x - h.barycentric.y);
      if (h.valid() && edge < 1e-3f) {
        ++embree_leaks;
        return;
      }
    }
    if (e != f && ++mismatches <= 5)
      ADD_FAILURE() << "occlusion differs (embree " << e << ", flat " << f << "): origin (" << r.origin.x << ", "
                    << r.origin.y << ", " << r.origin.z << ") dir (" << r.direction.x << ", " << r.direction.y << ", "
                    << r.direction.z << ") tmax " << r.tmax << ", closest t " << closest.t;
  };
  // Random segments, half of them ending just before or after the closest surface.
  for (Ray r : random_rays(scene, 4321u, ray_count)) {
    const Hit closest = accel.intersect(r);
    if (closest.valid() && rng.uniform() < 0.5f) r.tmax = closest.t * rng.uniform(0.5f, 1.5f);
    check(r);
  }
  // Shadow rays between surface points, as the renderer spawns them.
  auto surface_point = [&](vec3& p, vec3& ng) {
    const uvec3 t = scene.triangles[rng.engine() % scene.triangles.size()];
    float u = rng.uniform(), v = rng.uniform();
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    vec3 p0 = scene.positions[t.x], p1 = scene.positions[t.y], p2 = scene.positions[t.z];
    p = (1.0f - u - v) * p0 + u * p1 + v * p2;
    ng = glm::cross(p1 - p0, p2 - p0);
    float len = glm::length(ng);
    ng = len > 0.0f ? ng / len : vec3(0, 0, 1);
  };
  for (int i = 0; i < ray_count; ++i) {
    vec3 p, np, y, ny;
    surface_point(p, np);
    surface_point(y, ny);
    if (glm::dot(np, y - p) < 0.0f) np = -np;
    check(accel.shadow_ray(p, np, y, ny));
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_LE(embree_leaks, checked / 10000 + 1);
  EXPECT_GT(occluded, checked / 20);
  std::printf("[%s] occlusion rays: %d checked, %d occluded, %d mismatches, %d Embree leaks at edges\n", name, checked,
              occluded, mismatches, embree_leaks);
}

TEST(FlatBvh, CornellBoxInvariants) {
  for (bool splits : {false, true}) {
    SCOPED_TRACE(splits ? "spatial splits" : "no spatial splits");
    FlatBvh bvh = build_flat_bvh(cornell_box(), {.spatial_splits = splits});
    check_invariants(cornell_box(), bvh, splits);
    EXPECT_EQ(bvh.stats.skipped_triangles, 0u);
    EXPECT_LE(bvh.stats.max_leaf_size, 4u);
    EXPECT_EQ(bvh.stats.node_count, 2 * bvh.stats.leaf_count - 1);
  }
}

TEST(FlatBvh, CornellBoxClosestHitsEqualEmbree) {
  for (bool splits : {false, true}) {
    SCOPED_TRACE(splits ? "spatial splits" : "no spatial splits");
    check_against_embree(cornell_box(), build_flat_bvh(cornell_box(), {.spatial_splits = splits}), 100000,
                         splits ? "cornell-box sbvh" : "cornell-box");
  }
}

TEST(FlatBvh, CornellBoxOcclusionEqualsEmbree) {
  check_occlusion(cornell_box(), build_flat_bvh(cornell_box()), 50000, "cornell-box");
}

TEST(FlatBvh, RaysAlongCornellBoxEdges) {
  // Rays lying in the planes of two walls, along their common edge, from beyond its end: the
  // ray meets the wall in front of it at the corner vertex (or runs out of the open side).
  // Ill-conditioned for any intersector (Embree reports the coplanar triangles at the vertex, the
  // watertight test rejects a ray in a triangle's plane): what is required is a finite answer
  // on which closest hit and occlusion agree.
  const Scene& scene = cornell_box();
  FlatBvh bvh = build_flat_bvh(scene);
  int hits = 0, rays = 0;
  for (const uvec3& tri : scene.triangles)
    for (int i = 0; i < 3; ++i) {
      vec3 a = scene.positions[tri[i]], b = scene.positions[tri[(i + 1) % 3]];
      for (vec3 origin : {a - 0.25f * (b - a), glm::mix(a, b, 0.5f)}) {
        ++rays;
        FlatHit f = flat_bvh_intersect(bvh, origin, b - a, 0.0f, kInf);
        bool occ = flat_bvh_occluded(bvh, origin, b - a, 0.0f, kInf);
        EXPECT_EQ(occ, f.valid());
        if (f.valid()) {
          ++hits;
          EXPECT_TRUE(std::isfinite(f.t) && f.t >= 0.0f);
          EXPECT_TRUE(std::isfinite(f.barycentric.x) && std::isfinite(f.barycentric.y));
        }
      }
    }
  std::printf("[cornell-box] rays along edges: %d, hits %d\n", rays, hits);
  EXPECT_GT(hits, 0);
}

TEST(FlatBvh, CornellBoxRoomEdgesAndCornersAreClosed) {
  // The room's walls meet in concave edges and corners: every ray from inside the room aimed at a
  // point of such an edge or at a corner of the back wall hits at t <= 1, whichever wall takes it.
  const Scene& scene = cornell_box();
  FlatBvh bvh = build_flat_bvh(scene);
  Rng rng(2024u);
  int rays = 0, leaks = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec3 origin(rng.uniform(-0.99f, 0.99f), rng.uniform(0.01f, 1.99f), rng.uniform(-0.99f, 0.99f));
    const float sx = rng.engine() % 2 ? 1.0f : -1.0f, sy = rng.engine() % 2 ? 2.0f : 0.0f, s = rng.uniform(-1.0f, 1.0f);
    vec3 target;
    switch (i % 4) {
      case 0: target = vec3(sx, sy, -1.0f); break;                    // back corners
      case 1: target = vec3(sx, s + 1.0f, -1.0f); break;              // back wall / side walls
      case 2: target = vec3(s, sy, -1.0f); break;                     // back wall / floor, ceiling
      default: target = vec3(sx, sy, s * 0.999f); break;              // side walls / floor, ceiling
    }
    ++rays;
    const FlatHit f = flat_bvh_intersect(bvh, origin, target - origin, 0.0f, kInf);
    if (!(f.valid() && f.t <= 1.0f + 1e-4f) && ++leaks <= 5)
      ADD_FAILURE() << "leak at (" << target.x << ", " << target.y << ", " << target.z << ") from (" << origin.x << ", "
                    << origin.y << ", " << origin.z << "): t " << f.t;
    EXPECT_TRUE(flat_bvh_occluded(bvh, origin, target - origin, 0.0f, 1.0f + 1e-4f));
  }
  EXPECT_EQ(leaks, 0);
  std::printf("[cornell-box] rays at the room's edges and corners: %d, leaks %d\n", rays, leaks);
}

TEST(FlatBvh, EmptyAndDegenerateScenes) {
  Scene empty;
  empty.finalize_bounds();
  FlatBvh bvh = build_flat_bvh(empty);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_FALSE(flat_bvh_intersect(bvh, vec3(0), vec3(0, 0, 1), 0.0f, kInf).valid());
  EXPECT_FALSE(flat_bvh_occluded(bvh, vec3(0), vec3(0, 0, 1), 0.0f, kInf));

  // 5000 copies of one triangle (no split separates them) plus a zero-area one and a NaN one.
  Scene pile;
  pile.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}, {NAN, 0, 0}};
  for (int i = 0; i < 5000; ++i) pile.triangles.push_back({0, 1, 2});
  pile.triangles.push_back({3, 3, 3});
  pile.triangles.push_back({4, 1, 2});
  pile.triangle_material.assign(pile.triangles.size(), 0);
  FlatBvh p = build_flat_bvh(pile);
  EXPECT_EQ(p.stats.skipped_triangles, 1u);
  EXPECT_LE(p.stats.max_depth, uint32_t(BVH_STACK_SIZE));
  FlatHit h = flat_bvh_intersect(p, vec3(0.25f, 0.25f, 1.0f), vec3(0, 0, -1), 0.0f, kInf);
  ASSERT_TRUE(h.valid());
  EXPECT_LT(h.triangle, 5000u);
  EXPECT_FLOAT_EQ(h.t, 1.0f);
  EXPECT_FLOAT_EQ(h.barycentric.x, 0.25f);
  EXPECT_FLOAT_EQ(h.barycentric.y, 0.25f);
  EXPECT_FALSE(flat_bvh_intersect(p, vec3(2, 2, 3), vec3(0, 0, -1), 0.0f, kInf).valid());
  EXPECT_FALSE(flat_bvh_intersect(p, vec3(0.25f, 0.25f, 1.0f), vec3(0), 0.0f, kInf).valid());  // zero direction
}

TEST(FlatBvh, StaircaseEqualsEmbree) {
  const Scene* scene = staircase();
  if (!scene) GTEST_SKIP() << "shared scene staircase/staircase.gltf not present";
  EmbreeAccel accel(*scene);
  for (bool splits : {true, false}) {
    SCOPED_TRACE(splits ? "spatial splits" : "no spatial splits");
    FlatBvh bvh = build_flat_bvh(*scene, {.spatial_splits = splits});
    check_invariants(*scene, bvh, splits);
    const FlatBvhStats& s = bvh.stats;
    std::printf("[staircase%s] %zu triangles: build %.1f ms, %u nodes (%.1f MB), %u leaves, %u triangle refs "
                "(%.1f MB), max depth %u, max leaf %u\n",
                splits ? " sbvh" : "", scene->triangles.size(), s.build_ms, s.node_count,
                s.node_count * sizeof(glsl::BvhNode) / 1e6, s.leaf_count, s.triangle_refs,
                s.triangle_refs * sizeof(glsl::BvhTriangle) / 1e6, s.max_depth, s.max_leaf_size);
    // Single-thread C++ traversal speed against Embree's, on the same rays (informative).
    std::vector<Ray> rays = random_rays(*scene, 5u, 200000);
    auto t0 = std::chrono::steady_clock::now();
    uint32_t sink = 0;
    for (const Ray& r : rays) sink += flat_bvh_intersect(bvh, r.origin, r.direction, r.tmin, r.tmax).triangle;
    auto t1 = std::chrono::steady_clock::now();
    for (const Ray& r : rays) sink -= accel.intersect(r).triangle;
    auto t2 = std::chrono::steady_clock::now();
    std::printf("[staircase%s] %zu rays: flat BVH %.2f Mrays/s, Embree %.2f Mrays/s (one thread) %u\n",
                splits ? " sbvh" : "", rays.size(), rays.size() / std::chrono::duration<double, std::micro>(t1 - t0).count(),
                rays.size() / std::chrono::duration<double, std::micro>(t2 - t1).count(), sink & 0u);
    check_against_embree(*scene, bvh, 100000, splits ? "staircase sbvh" : "staircase");
  }
  check_occlusion(*scene, build_flat_bvh(*scene), 50000, "staircase");
}

TEST(FlatBvh, GlslTraversalCompiles) {
  if (test::run_command("command -v glslc").exit_code != 0) GTEST_SKIP() << "glslc not found";
  const auto source = std::filesystem::path(SST_SOURCE_DIR) / "gpu/shaders/bvh_trace_test.comp";
  const auto spv = test::temp_dir() / "bvh_trace_test.spv";
  // -I the source root, as the build compiles every shader: the layouts are included by their path there.
  auto result = test::run_command("glslc -I '" + std::string(SST_SOURCE_DIR) + "' '" + source.string() + "' -o '" +
                                  spv.string() + "' 2>&1");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(spv));
}

}  // namespace
}  // namespace sst
