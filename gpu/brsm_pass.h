// BRSM VPL generation on the GPU (VplParams::vpl_source = brsm): the twin of generate_brsm_vpls in
// core/brsm/brsm_generator.h, whose comment defines the set; the stages run in
// gpu/shaders/brsm.comp, one dispatch each (the G-buffer once, then per map its texels, filter,
// mip levels and warp), on buffers reused from map to map. The host plans the maps and compacts
// the draws exactly as the CPU does, so the set is the CPU's bits (with --accel flat).
#pragma once
#include <cstdint>

#include "core/scene/scene.h"
#include "core/brsm/brsm_layout.h"
#include "core/vpl/vpl.h"
#include "core/vpl/vpl_generator.h"
#include "gpu/bvh_upload.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// generate_brsm_vpls on the GPU, with generate_vpls_gpu's arguments (core/brsm/brsm_generator.h,
// gpu/vpl_generation_pass.h) and `lights` the PackedLights `gpu_lights` was uploaded from.
// stats->stage_ms holds the GPU time of each stage; stats->ms the wall time of the call.
VplSet generate_brsm_vpls_gpu(const VulkanContext& context, const GpuScene& gpu_scene, const GpuBvh& bvh,
                              const GpuLights& gpu_lights, const PackedLights& lights, const Scene& scene,
                              const VplParams& params, const ViewParams& view, uint32_t seed, bool diffuse_only,
                              VplStats* stats = nullptr, const EmissionFocus& focus = emission_focus_none(),
                              VkAccelerationStructureKHR top_level = VK_NULL_HANDLE);

}  // namespace sst::gpu
