// The flat BVH traversal on the GPU (gpu/shaders/bvh_trace_test.comp) against the same code run
// on the CPU (core/accel/flat_bvh.cpp): hits, distances and occlusion. Skips without a device.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <chrono>
#include <cmath>
#include <vector>

#include "core/accel/flat_bvh.h"
#include "core/pipeline/backend.h"
#include "core/rng/hash_rng.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gbuffer_pass.h"
#include "gpu/gpu_buffer.h"
#include "gpu/shader_library.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst::gpu {
namespace {

// Random rays from points inside the scene's bounds, uniform directions; a third end early.
std::vector<glsl::BvhRay> random_rays(const Scene& scene, uint32_t count) {
  Bounds3 b = scene.bounds;
  std::vector<glsl::BvhRay> rays(count);
  for (uint32_t i = 0; i < count; ++i) {
    HashRng rng = hash_rng(7, i, 0);
    vec3 o = b.lo + (b.hi - b.lo) * vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
    float z = 1.0f - 2.0f * hash_rng_next(rng), phi = 6.2831853f * hash_rng_next(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    rays[i] = {o, 0.0f, d, i % 3 == 0 ? 0.1f * b.diagonal() : kInf};
  }
  return rays;
}

void expect_gpu_equals_cpu(const Scene& scene, uint32_t count) {
  SKIP_WITHOUT_GPU("bvh_trace_test");
  FlatBvh bvh = build_flat_bvh(scene);
  std::vector<glsl::BvhRay> rays = random_rays(scene, count);
  VulkanContext context(0);
  GpuBvh gpu_bvh(context, bvh);
  GpuBuffer ray_buffer(context, rays.size() * sizeof(glsl::BvhRay));
  GpuBuffer hits(context, rays.size() * sizeof(glsl::BvhHit));
  GpuBuffer occluded(context, rays.size() * sizeof(uint32_t));
  ray_buffer.upload(std::span<const glsl::BvhRay>(rays));
  ComputePipeline pipeline(context, "bvh_trace_test", 5, 4);
  double gpu_ms = pipeline.dispatch({gpu_bvh.buffers()[0], gpu_bvh.buffers()[1], &ray_buffer, &hits, &occluded}, &count,
                                    (count + 63) / 64);
  std::vector<glsl::BvhHit> gpu_hits(count);
  std::vector<uint32_t> gpu_occluded(count);
  hits.download(std::span<glsl::BvhHit>(gpu_hits));
  occluded.download(std::span<uint32_t>(gpu_occluded));

  auto start = std::chrono::steady_clock::now();
  int hit_count = 0, t_mismatch = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const glsl::BvhRay& r = rays[i];
    Hit cpu = flat_bvh_intersect(bvh, r.origin, r.direction, r.tmin, r.tmax);
    bool cpu_blocked = flat_bvh_occluded(bvh, r.origin, r.direction, r.tmin, r.tmax);
    const glsl::BvhHit& g = gpu_hits[i];
    ASSERT_NE(g.triangle, BVH_STACK_OVERFLOW) << "ray " << i;
    ASSERT_EQ(g.triangle == BVH_INVALID_TRIANGLE, !cpu.valid()) << "ray " << i;
    EXPECT_EQ(gpu_occluded[i] == 1u, cpu_blocked) << "ray " << i;  // 1 = BVH_OCCLUDED (bvh_traverse.h)
    if (!cpu.valid()) continue;
    ++hit_count;
    // The same triangle, or a coincident one at the same t (coplanar faces); t to float order.
    if (std::abs(g.t - cpu.t) > 1e-5f * std::max(1.0f, cpu.t)) ++t_mismatch;
  }
  double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(t_mismatch, 0);
  EXPECT_GT(hit_count, int(count / 4));
  std::printf("%s: %u rays, %d hits; GPU (%s) %.2f ms, CPU flat-BVH traversal (1 thread) %.2f ms\n",
              scene.source.c_str(), count, hit_count, context.info().name.c_str(), gpu_ms, cpu_ms);
}

TEST(GpuBvh, TraversalOnTheGpuEqualsTheCpuOnTheCornellBox) { expect_gpu_equals_cpu(load_default_scene(), 50000); }

TEST(GpuBvh, TraversalOnTheGpuEqualsTheCpuOnTheStaircase) {
  auto path = test::shared_scene("staircase/staircase.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  expect_gpu_equals_cpu(load_gltf(path.string()), 50000);
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
