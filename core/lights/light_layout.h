// The tables of light sampling (core/lights/light_sample.h) as both backends read them, defined
// once for C++ and GLSL. LightSampler builds them (PackedLights, core/lights/light_sampler.h) from
// its DiscreteDistribution and reads them on the CPU; gpu/light_upload.h uploads them as they are
// and gpu/shaders/light_sampler.glsl binds the sampling's hooks to the buffers. In C++ the
// structures live in namespace sst::glsl (also named in sst) with static_asserts on size and
// offsets; in GLSL the same text declares plain std430 structs.
//
// Six std430 storage buffers, declared in GLSL by LIGHT_BUFFERS(first) under these names:
//   LightHeader       light_header            counts, the scene bounds and the light sampler
//                                             (one struct)
//   LightPunctual     light_punctual[]        Scene::lights[i] at index i
//   LightCdfEntry     light_distribution[]    entry i of the distribution over all lights:
//                                             punctual lights first, then emissive triangles
//   LightEmissive     light_emissive[]        emissive triangle k (distribution entry
//                                             punctual_count + k)
//   uint              light_of_triangle[]     scene triangle -> distribution entry, or
//                                             LIGHT_NONE for a triangle that does not emit
//   EmitterNode       light_tree[]            the emitter tree of the tree and slc samplers
//                                             (core/lights/emitter_tree.h): root 1, nodes
//                                             1 .. 2 tree_leaves - 1 linked by their
//                                             `children` and `parent`, then one node per
//                                             directional light; empty for the uniform and
//                                             power samplers
// An empty array is bound as a small dummy buffer; nothing indexes it.
//
// The distribution's CDF is summed in double. Each cdf value is kept as a pair of floats
// (hi = the nearest float, lo = the float nearest to the rest), so that `cdf > u` for a float u is
// decided exactly as with the double (hi > u, or hi == u and lo > 0): the same light is picked
// for the same u as a double CDF picks, on both backends.
#ifndef SST_CORE_LIGHTS_LIGHT_LAYOUT_H
#define SST_CORE_LIGHTS_LIGHT_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

// LightPunctual.type: sst::LightType.
#define LIGHT_POINT 0u
#define LIGHT_SPOT 1u
#define LIGHT_DIRECTIONAL 2u
// light_of_triangle[] of a triangle that is not a light.
#define LIGHT_NONE 0xFFFFFFFFu
// The number of buffers LIGHT_BUFFERS declares (sst::gpu::GpuLights::buffers()).
#define LIGHT_BUFFER_COUNT 6u

// LightHeader.sampler_kind: how light_sample picks a light for a shading point (sst::LightSamplerKind,
// RenderOptions::light_sampler). Emission (light paths, VPLs) always picks by power.
#define LIGHT_SAMPLER_UNIFORM 0u  // every light alike
#define LIGHT_SAMPLER_POWER 1u    // in proportion to power (the CDF of light_distribution[])
#define LIGHT_SAMPLER_TREE 2u     // down the emitter tree by pbrt-v4's / Conty Estevez & Kulla's importance
#define LIGHT_SAMPLER_SLC 3u      // down the same tree by Yuksel's (SLC) child weights

// LightHeader.tree_distance: the distance in the tree samplers' importance (core/lights/
// emitter_tree.h; RenderOptions::light_tree_distance).
#define EMITTER_DISTANCE_CENTRE 0u  // to the box's centre, at least a quarter of its bounding radius
#define EMITTER_DISTANCE_BOX 1u     // to the box, at least its bounding radius
#define EMITTER_DISTANCE_MIXED 2u   // to the box outside the bounding sphere, to the centre within it

// EmitterNode.flags.
#define EMITTER_TWO_SIDED 1u      // emits about +axis and -axis (a double-sided emissive triangle)
#define EMITTER_DIRECTIONAL 2u    // a directional light: `axis` is the direction its light travels

struct LightHeader {
  uint punctual_count;      // Scene::lights.size()
  uint emissive_count;      // the number of emissive triangles
  uint distribution_size;   // punctual_count + emissive_count; 0 when the distribution is empty
  uint triangle_count;      // entries of light_of_triangle[] (Scene::triangles.size())
  vec3 bounds_center;       // Scene::bounds.center(), for directional emission
  float bounds_radius;      // 0.5f * Scene::bounds.diagonal(), as the CPU computes it
  uint sampler_kind;        // LIGHT_SAMPLER_*
  uint tree_leaves;         // leaves of the emitter tree (morton build: padded to a power of two);
                            // 0 without a tree
  uint directional_count;   // directional lights; tree samplers: nodes 2 tree_leaves ..
  uint tree_distance;       // EMITTER_DISTANCE_*
};

// A node of the emitter tree: what every emitter below it may send toward a point, bounded.
// Leaves hold one light; an inner node bounds its two children, which lie side by side at
// `children` and `children + 1` (core/lights/emitter_tree_build.h lays them out); a padding leaf
// or a node over padding only has intensity 0 (and is never picked).
struct EmitterNode {
  vec3 lo;          // box of the emitters' points (a point light: its position)
  float intensity;  // summed luminance of the radiant intensity toward the axis: point and spot
                    // I, an emissive triangle Le A (its mean emission times its area), W/sr;
                    // a directional light: its irradiance, W/m^2
  vec3 hi;
  float cos_o;      // cosine of the normal-bound cone's half angle about `axis` (theta_o)
  vec3 axis;        // unit; the normals (emission axes) lie within theta_o of it
  float cos_e;      // cosine of theta_e: beyond theta_o + theta_e from the axis nothing is emitted
  uint flags;       // EMITTER_*
  uint entry;       // leaf: the distribution entry of its light; LIGHT_NONE otherwise
  uint children;    // inner node: the index of its first child; 0 for a leaf (node 0 is unused)
  uint parent;      // the index of its parent; 0 for the root and for a directional light
};

// One KHR_lights_punctual light (sst::PunctualLight), radiometric.
struct LightPunctual {
  vec3 position;
  uint type;         // LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL
  vec3 direction;    // unit, the direction the light travels
  float cos_inner;
  vec3 intensity;    // W/sr (point, spot) or W/m^2 (directional), per channel
  float cos_outer;
};

// Entry i of DiscreteDistribution: its cdf as hi + lo (see the top) and its pmf.
struct LightCdfEntry {
  float cdf_hi;  // float(cdf[i])
  float cdf_lo;  // float(cdf[i] - double(cdf_hi))
  float pmf;     // DiscreteDistribution::pmf(i): the power sampler's pick probability
  uint tree_node; // tree samplers: the node of light i in light_tree[]; LIGHT_NONE otherwise
};

// Emissive triangle k of LightSampler: the scene triangle and its area (as the CPU computed it).
struct LightEmissive {
  uint triangle;
  float area;
};

#ifdef __cplusplus
static_assert(sizeof(LightHeader) == 48);
static_assert(offsetof(LightHeader, bounds_center) == 16 && offsetof(LightHeader, bounds_radius) == 28);
static_assert(offsetof(LightHeader, sampler_kind) == 32 && offsetof(LightHeader, directional_count) == 40);
static_assert(offsetof(LightHeader, tree_distance) == 44);
static_assert(sizeof(EmitterNode) == 64 && offsetof(EmitterNode, hi) == 16 && offsetof(EmitterNode, cos_o) == 28);
static_assert(offsetof(EmitterNode, axis) == 32 && offsetof(EmitterNode, cos_e) == 44);
static_assert(offsetof(EmitterNode, flags) == 48 && offsetof(EmitterNode, entry) == 52);
static_assert(offsetof(EmitterNode, children) == 56 && offsetof(EmitterNode, parent) == 60);
static_assert(sizeof(LightPunctual) == 48);
static_assert(offsetof(LightPunctual, type) == 12 && offsetof(LightPunctual, direction) == 16);
static_assert(offsetof(LightPunctual, cos_inner) == 28 && offsetof(LightPunctual, intensity) == 32);
static_assert(offsetof(LightPunctual, cos_outer) == 44);
static_assert(sizeof(LightCdfEntry) == 16 && offsetof(LightCdfEntry, pmf) == 8);
static_assert(sizeof(LightEmissive) == 8 && offsetof(LightEmissive, area) == 4);
}  // namespace sst::glsl

namespace sst {
using glsl::EmitterNode;
using glsl::LightCdfEntry;
using glsl::LightEmissive;
using glsl::LightHeader;
using glsl::LightPunctual;
}  // namespace sst
#else
// Declares the six light buffers, read-only, at bindings first .. first + 5 in the order of the
// list at the top: the order of sst::gpu::GpuLights::buffers().
#define LIGHT_BUFFERS(first)                                                                              \
  layout(std430, binding = (first)) readonly buffer LightHeaderBuffer { LightHeader light_header; };     \
  layout(std430, binding = (first) + 1) readonly buffer LightPunctuals { LightPunctual light_punctual[]; }; \
  layout(std430, binding = (first) + 2) readonly buffer LightDistribution { LightCdfEntry light_distribution[]; }; \
  layout(std430, binding = (first) + 3) readonly buffer LightEmissives { LightEmissive light_emissive[]; };  \
  layout(std430, binding = (first) + 4) readonly buffer LightOfTriangle { uint light_of_triangle[]; };  \
  layout(std430, binding = (first) + 5) readonly buffer LightTree { EmitterNode light_tree[]; };
#endif

#endif  // SST_CORE_LIGHTS_LIGHT_LAYOUT_H
