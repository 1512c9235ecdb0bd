// BRSM VPL generation on the CPU (VplParams::vpl_source = brsm; the algorithm is core/brsm/brsm.h,
// docs/design/brsm.md): the camera's G-buffer, then per map its texels, their filtered weights,
// the mip chain and the warped draws, each stage a parallel loop over independent elements, so
// the set is the same bits for any thread count and equals the GPU's (gpu/brsm_pass.h).
//
// The set has exactly `vpls` VPLs, map by map in the order of brsm_maps(), each map's in the order
// of its Hammersley points. Its one-bounce light equals, in expectation, that of `paths` with
// vpl_max_bounces 1; light that bounces more than once is not in it.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"
#include "core/brsm/brsm_layout.h"
#include "core/vpl/vpl.h"
#include "core/vpl/vpl_generator.h"

namespace sst {

// The maps of a scene's lights, at most `max_maps` and at most `vpls`: one per light of nonzero
// power when they are few enough, else runs of consecutive lights of about equal power. Each
// map's VPL count is in proportion to its power (largest remainders, at least 1), summing to
// `vpls`. Empty when no light emits.
std::vector<BrsmMap> brsm_maps(const PackedLights& lights, int vpls, int max_maps);

// The side of the maps when brsm_resolution is 0: the smallest power of two, within 16..4096, whose
// square holds `texels_per_vpl` texels for each VPL of the map that draws the most.
uint32_t brsm_auto_resolution(const std::vector<BrsmMap>& maps, float texels_per_vpl);

// What a frame's set is drawn from, for both backends: its maps and the settings every stage reads.
struct BrsmPlan {
  std::vector<BrsmMap> maps;
  BrsmSettings settings;
};

// The plan of a frame (validate(params) first: sst::Error for impossible values); resets `stats`
// to an empty BRSM record.
BrsmPlan brsm_plan(const Scene& scene, const PackedLights& lights, const VplParams& params, const ViewParams& view,
                   uint32_t seed, bool diffuse_only, const EmissionFocus& focus, VplStats& stats);

// The order both backends run the stages in: the G-buffer, then per map its texels, filter, mip
// levels 1..top and warp. `step(stage, level, map)` runs every element of one stage (BRSM_STAGE_*;
// `level` 0 except for BRSM_STAGE_MIP); `map_done(map)` follows each map's warp. Nothing without
// maps.
void brsm_schedule(const BrsmPlan& plan, const std::function<void(uint32_t, uint32_t, uint32_t)>& step,
                   const std::function<void(uint32_t)>& map_done);

// The name of a stage in VplStats::stage_ms: gbuffer, texels, filter, mip, warp.
const char* brsm_stage_name(uint32_t stage);

// The set from the VPLs drawn from `map_count` maps of `settings`: those of zero intensity (drawn
// from a map whose texels all missed) left out, in order; fills `stats` (VPL count, per-bounce
// sums, maps, texels, rays, clamp) except stage and wall times.
VplSet brsm_finish(const VplSet& drawn, size_t map_count, const BrsmSettings& settings, const VplParams& params,
                   const Scene& scene, VplStats& stats);

// Throws sst::Error when validate(params) does.
VplSet generate_brsm_vpls(const Scene& scene, const EmbreeAccel& accel, const LightSampler& lights,
                          const VplParams& params, const ViewParams& view, uint32_t seed, bool diffuse_only,
                          VplStats* stats = nullptr, const EmissionFocus& focus = emission_focus_none());

}  // namespace sst
