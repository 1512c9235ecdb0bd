#include "gpu/brsm_pass.h"

#include <algorithm>
#include <chrono>
#include <span>
#include <vector>

#include "core/brsm/brsm_generator.h"
#include "core/vpl/light_path_layout.h"
#include "gpu/compute_pipeline.h"

namespace sst::gpu {
namespace {

constexpr uint32_t kGroupSize = 64;     // local_size_x of the shader
constexpr uint32_t kMaxGroups = 65535;  // the smallest maxComputeWorkGroupCount Vulkan allows

// Runs `invocations` of one stage as rows of at most kMaxGroups workgroups, which the shader
// numbers row by row (a 4096^2 map has 262 144 groups of texels); returns the GPU time. On
// lavapipe a buffer that large exceeds the 128 MiB storage-buffer range first (make_buffer's
// error), so only devices with larger ranges use more than one row.
double dispatch_stage(ComputePipeline& pipeline, const std::vector<const GpuBuffer*>& buffers, const BrsmPush& push,
                      uint32_t invocations) {
  const uint32_t groups = (invocations + kGroupSize - 1) / kGroupSize;
  const uint32_t x = std::min(groups, kMaxGroups);
  return pipeline.dispatch(buffers, &push, x, (groups + x - 1) / x);
}

}  // namespace

VplSet generate_brsm_vpls_gpu(const VulkanContext& context, const GpuScene& gpu_scene, const GpuBvh& bvh,
                              const GpuLights& gpu_lights, const PackedLights& lights, const Scene& scene,
                              const VplParams& params, const ViewParams& view, uint32_t seed, bool diffuse_only,
                              VplStats* stats, const EmissionFocus& focus, VkAccelerationStructureKHR top_level) {
  auto start = std::chrono::steady_clock::now();
  VplStats local;
  VplStats& st = stats ? *stats : local;
  const BrsmPlan plan = brsm_plan(scene, lights, params, view, seed, diffuse_only, focus, st);
  const std::vector<BrsmMap>& maps = plan.maps;
  const BrsmSettings& s = plan.settings;
  const uint32_t res = s.resolution, texel_count = res * res, top = brsm_top_level(res);
  VplSet drawn;
  uint64_t gbuffer_size = uint64_t(s.gbuffer_width) * s.gbuffer_height;
  if (!maps.empty()) {
    auto settings = upload_buffer(context, std::span<const BrsmSettings>(&s, 1), "BRSM settings");
    auto map_buffer = upload_buffer(context, maps, "BRSM maps");
    auto gbuffer = make_buffer(context, size_t(gbuffer_size), sizeof(BrsmGSample), "BRSM G-buffer");
    auto texels = make_buffer(context, texel_count, sizeof(BrsmTexel), "BRSM texels");
    auto mip = make_buffer(context, brsm_mip_offset(res, top + 1), 2 * sizeof(float), "BRSM mip chain");
    auto slots = make_buffer(context, size_t(params.vpls), sizeof(VplSlot), "BRSM VPLs");
    std::vector<const GpuBuffer*> buffers = gpu_scene.buffers();
    for (const GpuBuffer* b : bvh.buffers()) buffers.push_back(b);
    for (const auto* b : {&settings, &map_buffer, &gbuffer, &texels, &mip, &slots}) buffers.push_back(b->get());
    for (const GpuBuffer* b : gpu_lights.buffers()) buffers.push_back(b);
    ComputePipeline pipeline(context, "brsm", uint32_t(buffers.size()), sizeof(BrsmPush), {}, top_level);
    std::vector<BrsmTexel> map_texels(texel_count);
    brsm_schedule(
        plan,
        [&](uint32_t stage, uint32_t level, uint32_t m) {
          const BrsmPush push{stage, level, m, 0};
          add_stage_ms(st, brsm_stage_name(stage),
                       dispatch_stage(pipeline, buffers, push, brsm_stage_size(s, maps[m], stage, level)));
        },
        [&](uint32_t) {
          texels->download(std::span<BrsmTexel>(map_texels));
          for (const BrsmTexel& t : map_texels) st.pvpls += luminance(t.intensity) > 0.0f ? 1 : 0;
        });
    std::vector<VplSlot> out(size_t(params.vpls));
    slots->download(std::span<VplSlot>(out));
    drawn.reserve(out.size());
    for (const VplSlot& v : out) drawn.push_back({v.position, v.normal, v.intensity});
  }
  VplSet vpls = brsm_finish(drawn, maps.size(), s, params, scene, st);
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return vpls;
}

}  // namespace sst::gpu
