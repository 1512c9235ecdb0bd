// GI-1.0's data crossing the host/GPU boundary, defined once for C++ (namespace sst::glsl,
// static_asserts in gi10_state.cpp) and GLSL: the frame's constants (one read-only buffer, too big
// for push constants), the per-pixel G-buffer of pixel centres, the per-ray record of the probe
// rays, and the layout of the buffers every stage reads (gi10_stages.h).
#ifndef SST_CORE_GI10_GI10_LAYOUT_H
#define SST_CORE_GI10_GI10_LAYOUT_H
#include "core/math/cpu_gpu.h"
#include "core/render/frame_layout.h"

#ifdef __cplusplus
namespace sst::glsl {
using glm::uvec2;
using glm::vec4;
#endif

// Flags of Gi10Frame::flags: the switches in which the presets differ (gi10_params.h).
#define GI10_FEEDBACK 1u            // previous frame's image as radiance of on-screen cache points
#define GI10_PROBE_EMISSION 2u      // probe rays that hit an emitter return its emission and stop
#define GI10_BACKUP_MEAN 4u         // empty texels: the mean of the reached texels, not spread over them
#define GI10_SHORT_RAY_BIT 8u       // the short-ray bit in the cache key
#define GI10_BYPASS 16u             // probe rays shorter than a cell keep their own shadow-ray sample
#define GI10_BLUR_MASK_CAPSAICIN 32u  // the blur-mask dilation skips its centre row and column (B7)
#define GI10_PROBE_FILTER 64u       // filter probes across neighbours (S17; the driver skips its stages without it)
#define GI10_DENOISE 128u           // GI-1.0's temporal denoiser (S20); else E_out = interpolated E
#define GI10_GUIDING 256u           // probe rays guided by the reconstructed radiance; else one per texel
#define GI10_HYSTERESIS 512u        // traced texels blended with their reconstruction (paper Algorithm 3)
#define GI10_TEXEL_EXPECTED 1024u   // a texel's rays summed over the rays expected there, not averaged (no fill)
#define GI10_CACHE_LOOKUP 2048u     // probe rays read their cell's average; else each keeps its own sample
#define GI10_IRRADIANCE_TEXELS 4096u  // S19 integrates the probes' texels, not their L2 SH
#define GI10_WORLD_RESTIR 8192u     // cache points sample light by RIS with world-space temporal reuse
#define GI10_WORLD_RESTIR_UNBIASED 16384u  // ... merging with the shadow ray that keeps it unbiased
#define GI10_CACHE_PATHS 32768u     // cache points the feedback does not serve trace a path (every bounce)

// Stage numbers of the one GPU entry point (gpu/shaders/gi10.comp), in execution order.
#define GI10_STAGE_GBUFFER 0u
#define GI10_STAGE_PURGE 1u
#define GI10_STAGE_REPROJECT 2u
#define GI10_STAGE_SPAWN 3u
#define GI10_STAGE_SAMPLE 4u
#define GI10_STAGE_TRACE 5u
#define GI10_STAGE_SHADE 6u
#define GI10_STAGE_UPDATE 7u
#define GI10_STAGE_RESOLVE 8u
#define GI10_STAGE_BLEND 9u
#define GI10_STAGE_MASK_MIP 10u
#define GI10_STAGE_FILTER 11u
#define GI10_STAGE_PROJECT 12u
#define GI10_STAGE_INTERPOLATE 13u
#define GI10_STAGE_DENOISE_REPROJECT 14u
#define GI10_STAGE_BLUR_MASK 15u
#define GI10_STAGE_FILTER_GI 16u
#define GI10_STAGE_COPY_PROBES 17u
#define GI10_STAGE_FEEDBACK 18u
#define GI10_STAGE_EMPTY_TILES 19u
#define GI10_STAGE_LIST_COUNT 20u
#define GI10_STAGE_LIST_SCAN 21u
#define GI10_STAGE_LIST_COMPACT 22u
#define GI10_STAGE_PATCH 23u
#define GI10_STAGE_STORE_RESERVOIR 24u
#define GI10_STAGE_SIDE_LOOKUP 25u
#define GI10_STAGE_SIDE_ALLOCATE 26u
#define GI10_STAGE_SIDE_REORDER 27u
#define GI10_STAGES 28u
// SHADE's further shader builds (gpu/shaders/gi10.comp): build GI10_STAGE_SHADE shades a cache
// point by one light sample, these two by a path (GI10_CACHE_PATHS) and by world-space ReSTIR
// (GI10_WORLD_RESTIR); gi10_shade_build picks one. All three in one build made 1 MB of SPIR-V:
// lavapipe, which compiles at the first dispatch, took about 170 s over a cold first frame, and
// 24 s with the light-sample build.
#define GI10_SHADER_SHADE_PATHS 28u
#define GI10_SHADER_SHADE_RESTIR 29u
#define GI10_SHADER_BUILDS 30u

// Counters (Gi10 counters buffer, uint each).
#define GI10_COUNT_PROBES 0u          // spawned probes traced
#define GI10_COUNT_PATCHED 1u         // of them moved into empty tiles
#define GI10_COUNT_EMPTY 2u           // empty (disoccluded) tiles found
#define GI10_COUNT_PROBE_RAYS 3u
#define GI10_COUNT_HITS 4u
#define GI10_COUNT_INSERT_FAILED 5u   // bucket full: the ray's radiance is lost
#define GI10_COUNT_NEW_TILES 6u
#define GI10_COUNT_FEEDBACK 7u
#define GI10_COUNT_SHADOW_RAYS 8u
#define GI10_COUNT_BYPASS 9u
#define GI10_COUNT_EMISSIVE 10u
#define GI10_COUNT_EVICTED 11u
#define GI10_COUNT_LIVE_TILES 12u
#define GI10_COUNT_BLUR_WORK 13u      // S = sum over pixels of (2 m + 1)^2 (the denoiser's blur radius)
#define GI10_COUNT_RESERVOIRS_REUSED 14u  // world_restir: cache points that merged the previous frame's reservoir
#define GI10_COUNT_NO_HISTORY 15u     // spawned probes whose reconstruction found no texel (traced from scratch)
#define GI10_COUNT_SIDE_EVICTED 16u   // side_cache: spawned probes that evicted the previous probe of their tile
#define GI10_COUNT_SIDE_ALLOCATED 17u  // side_cache: slots taken from the front of the LRU order
#define GI10_COUNT_SIDE_USED 18u      // side_cache: spawned probes whose reconstruction a cached probe fed
#define GI10_COUNT_RELAXED 19u        // pixels whose irradiance came from probes off their surface (hint 0)
#define GI10_COUNT_NO_PROBE 20u       // surface pixels that found no probe at all (irradiance 0)
#define GI10_COUNTERS 24u

// Everything the stages read that is not a buffer. The host fills it once per frame.
struct Gi10Frame {
  ViewParams view;           // this frame's camera (core/render/frame_layout.h)
  ViewParams previous_view;  // the previous frame's; equal to view at frame 0
  uint width;
  uint height;
  uint tiles_x;              // screen tiles (8x8 pixels, one probe each)
  uint tiles_y;
  uint spawn_x;              // spawn tiles (16x16 pixels, one traced probe each)
  uint spawn_y;
  uint mask_levels;          // mips of the probe mask
  uint frame;                // index in the sequence: Halton jitter and random numbers
  uint seed;
  uint flags;                // GI10_*
  uint has_history;          // 0 at frame 0: nothing to reproject
  uint diffuse_only;
  uvec2 jitter16;            // this frame's spawn pixel inside a 16x16 spawn tile
  uvec2 jitter8;             // inside an 8x8 screen tile (patched probes)
  float scene_epsilon;       // SCENE_RAY_EPSILON (core/accel/ray_offset.h)
  float k_probe;             // tan(fov_y * probe_px * max(1/H, H/W^2)): screen cell size per unit distance
  float k_hash;              // the same for the cache's cell_px
  float min_cell;            // smallest cache cell, scene units
  int hash_base_exp;         // cache cell sizes are 2^hash_base_exp times a power of two
  uint num_buckets;
  uint tiles_per_bucket;
  float max_samples;         // cache cells' count cap (16)
  uint tile_decay;           // frames untouched after which a hash tile is freed (50)
  float sh_weight;           // per-texel quadrature weight of the SH projection (2 pi / 64)
  float reproject_normal;    // cos threshold of probe reprojection (0.95)
  float feedback_normal;     // cos threshold of the feedback's G-buffer test (0.5)
  float feedback_depth;      // its relative depth tolerance (0.05)
  float filter_angle;        // cos of the probe filter's parallax threshold (cos(0.02 pi))
  float interpolation_jitter;  // pixels (16)
  float denoise_history;     // the denoiser's history cap factor (8: cap = lerp(4, 8 min(n, 8), beta) vign)
  uint restir_candidates;    // world-space ReSTIR: light samples per cache point (8)
  float restir_cap;          // its history's M cap, in multiples of the new reservoir's (20)
  int path_bounces;          // cache_shading path: bounces counted from the pixel (8)
  uint side_slots;           // side_cache: its slots, as many as screen tiles; 0: off
};

// The G-buffer of a pixel centre: the first hit of the ray through the centre.
struct Gi10Pixel {
  vec3 position;
  float depth;       // linear view depth (along the camera's forward axis); 0 for a miss
  vec3 ng;           // geometric normal toward the camera; 0 for a miss
  uint ns;           // shading normal toward the camera, octahedral (gi_oct_encode)
};

// Flags of Gi10Ray::flags.
#define GI10_RAY_ACTIVE 1u     // its probe was spawned: the ray is traced
#define GI10_RAY_HIT 2u
#define GI10_RAY_CELL 4u       // it got a cache cell (cell is valid)
#define GI10_RAY_FEEDBACK 8u   // its radiance came from the previous frame's image
#define GI10_RAY_SHADOW 16u    // it traced a shadow ray from its hit
#define GI10_RAY_BYPASS 32u    // shorter than a cell: keeps its own sample
#define GI10_RAY_EMISSIVE 64u  // it hit an emitter and returns the emission
#define GI10_RAY_RESERVOIR 128u  // its light sample is a world-space ReSTIR reservoir (RAY_RESERVOIRS)

// One probe ray: the direction chosen by the sample stage, its probe's reconstructed texel (for
// the hysteresis), the secondary vertex and the radiance it brings back. The record of lane c also
// carries texel c's reconstruction and expected ray count, whichever texel the ray itself lands in.
struct Gi10Ray {
  vec3 direction;
  float recon_distance;  // the reconstruction's mean hit distance in texel <lane>; < 0: none
  vec3 recon;            // the reconstruction's radiance in texel <lane>
  float t;               // hit distance; kGiMissDistance for a miss
  vec3 x2;               // the secondary vertex
  uint cell;             // its cache cell (mip 0 index); valid with GI10_RAY_CELL
  vec3 n2;               // geometric normal at x2, toward the ray's origin
  uint flags;
  vec3 ns2;              // shading normal at x2, same side
  uint texel;            // the texel of its probe the ray's direction lands in
  vec3 albedo2;          // base colour at x2
  float cell_size;       // edge of its cache cell (the bypass test)
  vec3 radiance;         // what the ray brings back to its probe
  float expected;        // how many of its probe's 64 rays are expected to land in texel <its lane>
  vec3 lift;             // Surface::lift at x2 (shadow rays from it)
  float offset;          // Surface::offset at x2
};

// Push constants of gpu/shaders/gi10.comp: which stage, and its pass (filter direction, mip).
struct Gi10Push {
  uint stage;
  uint pass;
  uint count;  // invocations of the dispatch
  uint pad0;
};

// The shader build of SHADE for a frame's flags (GI10_SHADER_BUILDS).
SST_FUNC uint gi10_shade_build(uint flags) {
  if ((flags & GI10_CACHE_PATHS) != 0u) return GI10_SHADER_SHADE_PATHS;
  return (flags & GI10_WORLD_RESTIR) != 0u ? GI10_SHADER_SHADE_RESTIR : GI10_STAGE_SHADE;
}

#ifdef __cplusplus
}  // namespace sst::glsl
#endif

#endif  // SST_CORE_GI10_GI10_LAYOUT_H
