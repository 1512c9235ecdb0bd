#include "gpu/gpu_render_context.h"

#include <chrono>

#include "core/accel/embree_accel.h"
#include "core/accel/flat_bvh.h"
#include "core/util/error.h"

namespace sst::gpu {
namespace {
double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

GpuRenderContext::GpuRenderContext(int device, const Scene& scene, const LightSampler& lights, const FlatBvh& flat,
                                   const std::string& accel)
    : vulkan_(device), ray_epsilon_(scene_ray_epsilon(scene)) {
  if (accel != "flat" && accel != "rayquery" && accel != "auto")
    throw Error("unknown GPU accel '" + accel + "' (valid: flat, rayquery, auto)");
  const bool gpu = vulkan_.info().type != "cpu";
  accel_ = accel == "auto" ? (gpu && vulkan_.info().ray_query ? "rayquery" : "flat") : accel;
  bvh_build_ms_ = flat.stats.build_ms;
  bvh_nodes_ = flat.nodes.size();
  auto t0 = std::chrono::steady_clock::now();
  scene_ = std::make_unique<GpuScene>(vulkan_, scene);
  bvh_ = std::make_unique<GpuBvh>(vulkan_, flat);
  lights_ = std::make_unique<GpuLights>(vulkan_, scene, lights);
  upload_ms_ = ms_since(t0);
  if (accel_ == "rayquery") structure_ = std::make_unique<GpuAccelerationStructure>(vulkan_, scene);
}

std::unique_ptr<ComputePipeline> GpuRenderContext::make_pipeline(const std::string& shader, uint32_t buffer_count,
                                                                 uint32_t push_constant_bytes,
                                                                 std::vector<uint32_t> specialization) const {
  return std::make_unique<ComputePipeline>(vulkan_, shader, buffer_count, push_constant_bytes,
                                           std::move(specialization), top_level());
}

std::vector<const GpuBuffer*> GpuRenderContext::scene_buffers() const {
  std::vector<const GpuBuffer*> buffers = scene_->buffers();
  for (const GpuBuffer* b : bvh_->buffers()) buffers.push_back(b);
  for (const GpuBuffer* b : lights_->buffers()) buffers.push_back(b);
  return buffers;
}

nlohmann::json GpuRenderContext::describe() const {
  nlohmann::json d = {
      {"accel", accel_},
      {"bvh", {{"built_on", "cpu"}, {"builder", "embree rtcBuildBVH (SAH, spatial splits)"}, {"nodes", bvh_nodes_},
               {"build_ms", bvh_build_ms_}, {"bytes", bvh_->bytes()}}},
      {"upload_ms", upload_ms_},
      {"scene_bytes", scene_->bytes() + bvh_->bytes() + lights_->bytes()}};
  if (structure_) d["acceleration_structure"] = structure_->describe();
  return d;
}

}  // namespace sst::gpu
