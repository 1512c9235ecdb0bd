#include "gpu/gpu_render_context.h"

#include <chrono>

#include "core/accel/embree_accel.h"
#include "core/accel/flat_bvh.h"

namespace sst::gpu {
namespace {
double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

GpuRenderContext::GpuRenderContext(int device, const Scene& scene, const LightSampler& lights, const FlatBvh& flat)
    : vulkan_(device), ray_epsilon_(scene_ray_epsilon(scene)) {
  bvh_build_ms_ = flat.stats.build_ms;
  bvh_nodes_ = flat.nodes.size();
  auto t0 = std::chrono::steady_clock::now();
  scene_ = std::make_unique<GpuScene>(vulkan_, scene);
  bvh_ = std::make_unique<GpuBvh>(vulkan_, flat);
  lights_ = std::make_unique<GpuLights>(vulkan_, scene, lights);
  upload_ms_ = ms_since(t0);
}

std::vector<const GpuBuffer*> GpuRenderContext::scene_buffers() const {
  std::vector<const GpuBuffer*> buffers = scene_->buffers();
  for (const GpuBuffer* b : bvh_->buffers()) buffers.push_back(b);
  for (const GpuBuffer* b : lights_->buffers()) buffers.push_back(b);
  return buffers;
}

nlohmann::json GpuRenderContext::describe() const {
  return {{"bvh", {{"built_on", "cpu"}, {"builder", "embree rtcBuildBVH (SAH, spatial splits)"}, {"nodes", bvh_nodes_},
                   {"build_ms", bvh_build_ms_}}},
          {"upload_ms", upload_ms_},
          {"scene_bytes", scene_->bytes() + bvh_->bytes() + lights_->bytes()}};
}

}  // namespace sst::gpu
