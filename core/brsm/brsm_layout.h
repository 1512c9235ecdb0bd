// BRSM VPL generation's data crossing the host/GPU boundary (core/brsm/brsm.h is the algorithm,
// core/brsm/brsm_generator.cpp the CPU's executor, gpu/brsm_pass.cpp and gpu/shaders/brsm.comp
// the GPU's), defined once for C++ and GLSL.
#ifndef SST_CORE_BRSM_BRSM_LAYOUT_H
#define SST_CORE_BRSM_BRSM_LAYOUT_H
#include "core/math/cpu_gpu.h"
#include "core/render/frame_layout.h"

#ifdef __cplusplus
namespace sst {
using glsl::ViewParams;
}
#endif

SST_BEGIN

SST_CONSTANT uint kBrsmTraceStream = 0x4252534Du;  // "BRSM": a texel's light ray and G-buffer samples
SST_CONSTANT uint kBrsmWarpStream = 0x42525357u;   // "BRSW": a map's rotation of the Hammersley set

// The stages of one map, in order (BrsmPush::stage); the G-buffer comes once before every map.
SST_CONSTANT uint BRSM_STAGE_GBUFFER = 0u;  // one invocation per G-buffer pixel
SST_CONSTANT uint BRSM_STAGE_TEXELS = 1u;   // per texel: its light ray, its pVPL and importance
SST_CONSTANT uint BRSM_STAGE_FILTER = 2u;   // per texel: the filtered importance, mip level 0
SST_CONSTANT uint BRSM_STAGE_MIP = 3u;      // per texel of mip level BrsmPush::level (>= 1)
SST_CONSTANT uint BRSM_STAGE_WARP = 4u;     // per VPL of the map: a warped point, its VPL

// Where level `level` of a map's mip chain starts: level 0 is the map (resolution^2 entries, row-
// major), each next level half as wide, up to level log2(resolution) with one entry.
SST_FUNC uint brsm_mip_offset(uint resolution, uint level) {
  uint offset = 0u;
  uint side = resolution;
  for (uint k = 0u; k < level; ++k) {
    offset += side * side;
    side = side >> 1u;
  }
  return offset;
}

// log2(resolution): the level of the chain's single entry.
SST_FUNC uint brsm_top_level(uint resolution) { return uint(findMSB(resolution)); }

// What the camera sees at one pixel of the BRSM's G-buffer (its centre ray's first hit).
struct BrsmGSample {
  vec3 position;
  float hit;  // 1: a surface, 0: nothing (the other fields are 0)
  vec3 normal;  // shading normal, facing the camera
  float pad0;
  vec3 albedo;  // the diffuse albedo a VPL's light reflects with (vpl_albedo)
  float pad1;
};

// One texel of a map: its potential VPL (pVPL), the first hit of the texel's light ray, and the
// pVPL's estimated contribution to what the camera sees.
struct BrsmTexel {
  vec3 position;
  float importance;  // luminance, summed over the G-buffer samples / their count (0: no pVPL)
  vec3 normal;       // unit, on the side the light came from
  float pad0;
  vec3 intensity;    // the pVPL's intensity as a VPL that stands for its texel alone
  float pad1;
};

// One map: a contiguous range of lights of the power distribution, and its share of the VPLs.
struct BrsmMap {
  uint first_light;  // distribution entries first_light .. end_light - 1
  uint end_light;
  float cdf_start;   // the distribution's CDF before first_light
  float pmf_sum;     // the entries' summed pick probability (the share of power the map holds)
  uint vpl_offset;   // the map's first VPL in the output
  uint vpl_count;    // VPLs drawn from the map (>= 1)
  uint pad0;
  uint pad1;
};

// What every stage reads (CPU: an argument; GPU: a one-element storage buffer).
struct BrsmSettings {
  ViewParams view;      // the camera whose G-buffer weighs the pVPLs
  vec3 focus_center;    // the EmissionFocus of directional lights (core/lights/light_sample.h)
  float focus_radius;
  uint seed;
  uint resolution;      // texels per side of a map (a power of two)
  uint gbuffer_width;
  uint gbuffer_height;
  uint gbuffer_samples; // VplParams::brsm_gbuffer_samples
  float radius;         // VplParams::brsm_radius
  float power_fraction; // VplParams::brsm_power_fraction
  uint edge_filter;     // VplParams::brsm_filter
  uint diffuse_only;
  float ray_epsilon;    // scene_ray_epsilon(scene)
  uint screen_samples;  // VplParams::brsm_screen_samples
  uint pad0;
};

// The push constants of gpu/shaders/brsm.comp: which stage of which map.
struct BrsmPush {
  uint stage;      // BRSM_STAGE_*
  uint level;      // BRSM_STAGE_MIP: the level written
  uint map_index;  // into the maps buffer
  uint pad0;
};

// The elements of stage `stage` (BRSM_STAGE_*) of map `map`; `level`: BRSM_STAGE_MIP's level.
SST_FUNC uint brsm_stage_size(SST_IN(BrsmSettings) s, SST_IN(BrsmMap) map, uint stage, uint level) {
  if (stage == BRSM_STAGE_GBUFFER) return s.gbuffer_width * s.gbuffer_height;
  if (stage == BRSM_STAGE_TEXELS || stage == BRSM_STAGE_FILTER) return s.resolution * s.resolution;
  if (stage == BRSM_STAGE_MIP) return (s.resolution >> level) * (s.resolution >> level);
  return stage == BRSM_STAGE_WARP ? map.vpl_count : 0u;
}

SST_END

#ifdef __cplusplus
#include <cstddef>
static_assert(sizeof(sst::BrsmGSample) == 48);
static_assert(sizeof(sst::BrsmTexel) == 48);
static_assert(sizeof(sst::BrsmMap) == 32);
static_assert(sizeof(sst::BrsmSettings) == 80 + 16 + 48);
static_assert(sizeof(sst::BrsmPush) == 16);
#endif

#endif  // SST_CORE_BRSM_BRSM_LAYOUT_H
