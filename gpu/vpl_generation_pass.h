// Instant-radiosity VPL generation on the GPU (issue 5): the twin of generate_vpls in
// core/vpl/vpl_generator.h, whose long comment defines the set (exact VPL count, path i a pure
// function of (seed, i), intensities divided by P, kMaxPathsPerVpl). The light paths run in
// gpu/shaders/vpl_generation.comp, in batches of consecutive path indices; the host reads each
// batch's per-path counts, concatenates the deposits in path order until `vpls` exist, and fills
// VplStats as the CPU does. The set does not depend on the batching; only paths_traced and rays
// (work done past the last path used) do, as on the CPU, whose batches are other sizes.
#pragma once
#include <cstdint>

#include "core/scene/scene.h"
#include "core/vpl/vpl.h"
#include "core/vpl/vpl_generator.h"
#include "gpu/bvh_upload.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// generate_vpls on the GPU: `scene` is what `gpu_scene`, `bvh` and `lights` were built from (its
// bounds give the ray offsets, its VPL bounds the clamp distance). `gpu_ms` (optional) receives
// the GPU time of all dispatches; stats->ms is the wall time of the whole call.
// `max_batch_paths` > 0 caps the paths of one batch below what the device allows (tests: the set
// is the same for any batching). Throws sst::Error when validate(params) does, or when a batch
// cannot be allocated. `focus`: generate_vpls'. `top_level`: the scene's acceleration structure,
// to trace the light paths with ray queries instead of the flat BVH (GpuRenderContext::top_level).
VplSet generate_vpls_gpu(const VulkanContext& context, const GpuScene& gpu_scene, const GpuBvh& bvh,
                         const GpuLights& lights, const Scene& scene, const VplParams& params, uint32_t seed,
                         bool diffuse_only, VplStats* stats = nullptr, double* gpu_ms = nullptr,
                         uint64_t max_batch_paths = 0, const EmissionFocus& focus = emission_focus_none(),
                         VkAccelerationStructureKHR top_level = VK_NULL_HANDLE);

// Paths of the next batch, given the VPLs still missing and those deposited by the paths traced
// so far (exposed for tests). The first batch assumes half of min(vpl_min_bounces,
// vpl_max_bounces) deposits per path, at least 1 (paths that escape or end on black surfaces
// before roulette starts are common: 1.9 per path on the Cornell box with its open front, 3.1
// on the breakfast room), so that one batch usually suffices at the price of tracing up to about
// twice the paths needed; later batches extrapolate the measured rate, with 1% and 256 paths to
// spare, as the CPU does.
uint64_t vpl_batch_paths(uint64_t remaining, uint64_t deposited, uint64_t traced, const VplParams& params);

}  // namespace sst::gpu
