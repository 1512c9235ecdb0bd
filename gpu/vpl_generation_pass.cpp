#include "gpu/vpl_generation_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/util/error.h"
#include "core/vpl/vpl_clamp.h"
#include "core/vpl/light_path_layout.h"
#include "gpu/compute_pipeline.h"

namespace sst::gpu {
namespace {

// Per path: (deposits, rays); deposits == kLightPathOverflow: the BVH stack overflowed.
struct PathRecord {
  uint32_t deposits;
  uint32_t rays;
};

constexpr uint32_t kGroupSize = 64;           // local_size_x of the shader
constexpr uint64_t kMaxGroups = 65535;        // the smallest maxComputeWorkGroupCount[0] Vulkan allows
constexpr uint64_t kSparePaths = 256;         // added to each estimate (the CPU's chunk)
constexpr size_t kMaxBatchBytes = size_t(256) << 20;  // host-visible memory per batch, at most

// Paths one batch may hold: the slots buffer within the device's storage-buffer range (lavapipe:
// 128 MiB) and kMaxBatchBytes, the dispatch within one row of workgroups.
uint64_t batch_capacity(const VulkanContext& context, int max_bounces) {
  size_t limit = std::min<size_t>(size_t(context.info().max_storage_buffer_range), kMaxBatchBytes);
  uint64_t by_memory = uint64_t(limit / (sizeof(VplSlot) * size_t(max_bounces)));
  return std::max<uint64_t>(1, std::min(by_memory, kMaxGroups * kGroupSize));
}

// What the batches have produced so far, in path order.
struct Gathered {
  VplSet vpls;                // intensities not yet divided by the path count
  std::vector<uint16_t> hit;  // surface-hit index of each VPL (0: first hit)
  uint64_t paths = 0;         // P once `vpls` is complete, else 0
  uint64_t traced = 0;
  uint64_t deposited = 0;     // by all traced paths, surplus included (for the batch estimate)
  uint64_t rays = 0;
};

// Appends one batch (paths first .. first + records.size() - 1) to `g`: each path's deposits in
// hit order, up to the path that completes `target`, whose surplus is dropped; later paths count
// only for rays.
void gather(std::span<const PathRecord> records, const VplSlot* slots, int max_bounces, uint64_t target,
            Gathered& g) {
  for (size_t i = 0; i < records.size(); ++i) {
    const PathRecord& r = records[i];
    if (r.deposits == kLightPathOverflow)
      throw Error("VPL generation on the GPU: BVH traversal stack overflow on light path " +
                  std::to_string(g.traced + i));
    g.rays += r.rays;
    g.deposited += r.deposits;
    if (g.vpls.size() >= target) continue;
    size_t take = size_t(std::min<uint64_t>(r.deposits, target - g.vpls.size()));
    const VplSlot* s = slots + i * size_t(max_bounces);
    for (size_t k = 0; k < take; ++k) {
      g.vpls.push_back({s[k].position, s[k].normal, s[k].intensity});
      g.hit.push_back(uint16_t(k));
    }
    if (g.vpls.size() >= target) g.paths = g.traced + i + 1;
  }
  g.traced += records.size();
}

// Divides every intensity by the path count and fills the statistics, as assemble() in
// core/vpl/vpl_generator.cpp.
void finish(Gathered& g, uint64_t target, uint64_t max_paths, int max_hits, VplStats& stats) {
  stats.paths = g.vpls.size() >= target ? g.paths : g.traced;
  stats.paths_traced = g.traced;
  stats.rays = g.rays;
  stats.path_limit_reached = max_paths > 0 && g.vpls.size() < target && stats.paths >= max_paths;
  stats.vpls_per_bounce.assign(size_t(max_hits), 0);
  stats.intensity_per_bounce.assign(size_t(max_hits), dvec3(0.0));
  stats.vpls = g.vpls.size();
  if (stats.paths == 0) return;
  const float inv_paths = float(1.0 / double(stats.paths));
  for (size_t i = 0; i < g.vpls.size(); ++i) {
    g.vpls[i].intensity *= inv_paths;
    ++stats.vpls_per_bounce[g.hit[i]];
    stats.intensity_per_bounce[g.hit[i]] += dvec3(g.vpls[i].intensity);
  }
}

}  // namespace

uint64_t vpl_batch_paths(uint64_t remaining, uint64_t deposited, uint64_t traced, const VplParams& params) {
  if (traced == 0) {
    double per_path = std::max(1.0, 0.5 * double(std::min(params.vpl_min_bounces, params.vpl_max_bounces)));
    return uint64_t(std::ceil(double(remaining) / per_path)) + kSparePaths;
  }
  if (deposited == 0) return 4 * traced;
  double per_path = double(deposited) / double(traced);
  return uint64_t(1.01 * double(remaining) / per_path) + kSparePaths;
}

VplSet generate_vpls_gpu(const VulkanContext& context, const GpuScene& gpu_scene, const GpuBvh& bvh,
                         const GpuLights& lights, const Scene& scene, const VplParams& params, uint32_t seed,
                         bool diffuse_only, VplStats* stats, double* gpu_ms, uint64_t max_batch_paths,
                         const EmissionFocus& focus, VkAccelerationStructureKHR top_level) {
  validate(params);
  auto start = std::chrono::steady_clock::now();
  VplStats local;
  VplStats& st = stats ? *stats : local;
  st = VplStats{};
  if (gpu_ms) *gpu_ms = 0.0;
  const uint64_t target = uint64_t(params.vpls);
  const uint64_t max_paths = lights.header().distribution_size == 0 ? 0 : kMaxPathsPerVpl * target;
  const int max_bounces = params.vpl_max_bounces;
  Gathered g;
  if (max_paths > 0) {
    std::vector<const GpuBuffer*> buffers = gpu_scene.buffers();
    for (const GpuBuffer* b : bvh.buffers()) buffers.push_back(b);
    const size_t slots_binding = buffers.size();
    buffers.resize(slots_binding + 2);  // slots and path records, bound per batch
    for (const GpuBuffer* b : lights.buffers()) buffers.push_back(b);
    ComputePipeline pipeline(context, "vpl_generation", uint32_t(buffers.size()), sizeof(VplGenerationPush), {},
                             top_level);
    uint64_t capacity = batch_capacity(context, max_bounces);
    if (max_batch_paths > 0) capacity = std::min(capacity, max_batch_paths);
    VplGenerationPush push{seed, 0, 0, uint32_t(max_bounces), uint32_t(params.vpl_min_bounces), diffuse_only ? 1u : 0u,
                 scene_ray_epsilon(scene), params.focus_bounces, focus.center, focus.radius};
    std::vector<PathRecord> records;
    while (g.vpls.size() < target && g.traced < max_paths) {
      uint64_t batch = vpl_batch_paths(target - g.vpls.size(), g.deposited, g.traced, params);
      batch = std::min({batch, capacity, max_paths - g.traced});
      GpuBuffer slots(context, size_t(batch) * size_t(max_bounces) * sizeof(VplSlot));
      GpuBuffer paths(context, size_t(batch) * sizeof(PathRecord));
      buffers[slots_binding] = &slots;
      buffers[slots_binding + 1] = &paths;
      push.first_path = uint32_t(g.traced);
      push.path_count = uint32_t(batch);
      double ms = pipeline.dispatch(buffers, &push, uint32_t((batch + kGroupSize - 1) / kGroupSize));
      if (gpu_ms) *gpu_ms += ms;
      records.resize(size_t(batch));
      paths.download(std::span<PathRecord>(records));
      gather(records, static_cast<const VplSlot*>(slots.data()), max_bounces, target, g);
    }
  }
  finish(g, target, max_paths, max_bounces, st);
  set_clamp(params, g.vpls, scene, st);
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return std::move(g.vpls);
}

}  // namespace sst::gpu
