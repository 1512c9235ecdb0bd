// VPL generation's data crossing the host/GPU boundary (gpu/vpl_generation_pass.cpp and
// gpu/shaders/vpl_generation.comp), defined once for C++ and GLSL: the constants of a light path
// (core/vpl/light_path.h), the slot one deposit is written to and the push constants.
#ifndef SST_CORE_VPL_LIGHT_PATH_LAYOUT_H
#define SST_CORE_VPL_LIGHT_PATH_LAYOUT_H
#include "core/math/cpu_gpu.h"

SST_BEGIN

SST_CONSTANT uint kVplStream = 0x56504C31u;  // "VPL1"
// trace_light_path's deposit count for a path whose traversal gave up (a BVH stack overflow).
SST_CONSTANT uint kLightPathOverflow = 0xFFFFFFFFu;

// One deposit: position, normal (unit, on the side the light came from), intensity.
struct VplSlot {
  vec3 position;
  float pad0;
  vec3 normal;
  float pad1;
  vec3 intensity;
  float pad2;
};

// The push constants of vpl_generation.comp.
struct VplGenerationPush {
  uint seed;
  uint first_path;    // path index of invocation 0
  uint path_count;    // invocations that trace a path
  uint max_bounces;   // VplParams::vpl_max_bounces (slots per path)
  uint min_bounces;   // VplParams::vpl_min_bounces
  uint diffuse_only;
  float ray_epsilon;  // scene_ray_epsilon(scene)
  float focus_bounces;  // VplParams::focus_bounces
  vec3 focus_center;    // the EmissionFocus of directional lights (core/lights/light_sample.h)
  float focus_radius;
};

SST_END

#ifdef __cplusplus
#include <cstddef>
static_assert(sizeof(sst::VplSlot) == 48);
static_assert(offsetof(sst::VplSlot, normal) == 16 && offsetof(sst::VplSlot, intensity) == 32);
static_assert(sizeof(sst::VplGenerationPush) == 48 && offsetof(sst::VplGenerationPush, focus_center) == 32);
#endif

#endif  // SST_CORE_VPL_LIGHT_PATH_LAYOUT_H
