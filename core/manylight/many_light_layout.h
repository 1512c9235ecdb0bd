// The many-light samplers' inputs, defined once for C++ (static_asserts) and GLSL: the VPLs, the
// light tree's nodes (core/lighttree/light_node.h), the per-block cuts of rtslc and the hybrid
// with the G-buffer samples they were built for, the hybrid's mock cut, and one SamplerParams
// saying which sampler runs and with what. IndirectSampler::prepare builds all of it
// (SamplerInputs, sampler_inputs.h); the estimators (<name>/<name>_estimate.h) read it on the CPU,
// and gpu/many_light_upload.h uploads it for gpu/shaders/indirect_sampler.glsl.
//
// Buffers, std430, in the order of MANY_LIGHT_BUFFERS(first) (and GpuManyLightInputs::buffers()):
//   first + 0  SamplerParams ml_params        one element
//   first + 1  GpuVpl        ml_vpls[]        VplSet, index for index
//   first + 2  LightNode     ml_nodes[]       LightTree::node(i) for every node, leaves included
//   first + 3  uint          ml_cut_nodes[]   BlockCuts::nodes (block b: [b max_size, +sizes[b]))
//   first + 4  uint          ml_cut_sizes[]   BlockCuts::sizes
//   first + 5  CutGuide      ml_cut_guides[]  BlockCuts::guides
//   first + 6  uint          ml_mock_cut[]    HybridSampler::mock_cut()
// Arrays a sampler does not use are bound as 16-byte dummies and never read.
#ifndef SST_CORE_MANYLIGHT_MANY_LIGHT_LAYOUT_H
#define SST_CORE_MANYLIGHT_MANY_LIGHT_LAYOUT_H

#include "core/lighttree/light_node.h"
#include "core/manylight/many_light_methods.h"
#include "core/math/cpu_gpu.h"

SST_BEGIN

#define MANY_LIGHT_BUFFER_COUNT 7

// SamplerParams.method: which method's estimate estimate_indirect runs, ML_METHOD_<name> for each
// method of the list. C++ only: GLSL's switch takes the list's ids as they are, since global
// constants in a shader make glslang's `precise` propagation take all memory.
#ifdef __cplusplus
#define ML_DECLARE_METHOD_ID(name, id) SST_CONSTANT uint ML_METHOD_##name = id;
SST_MANY_LIGHT_METHODS(ML_DECLARE_METHOD_ID)
#undef ML_DECLARE_METHOD_ID
#endif

// SamplerParams.rtslc_weights (sst::RtslcWeights).
#define ML_RTSLC_WEIGHTS_RTSLC 0u
#define ML_RTSLC_WEIGHTS_SLC 1u

// One VPL (sst::Vpl), each vec3 padded to 16 bytes.
struct GpuVpl {
  vec3 position;
  float pad0;
  vec3 normal;  // unit
  float pad1;
  vec3 intensity;
  float pad2;
};

// The G-buffer sample a block's cut was built for (sst::GBufferSample, block_cuts.h).
struct CutGuide {
  vec3 p;
  uint valid;  // 0: the guide ray left the scene
  vec3 n;      // shading normal on the viewer's side
  float pad;
};

// Everything the samplers read besides the arrays. Fields a method does not use are 0.
struct SamplerParams {
  uint method;           // ML_METHOD_<name>
  uint vpl_count;        // ml_vpls[] length
  float clamp_distance;  // VplLighting::clamp_distance: c = vpl_clamp_at(this, clamp_per_depth, depth)
  uint tree_root;        // LightTree::root (tree samplers); kNoNode for an empty tree
  uint tree_first_leaf;  // LightTree::first_leaf
  uint tree_node_count;  // ml_nodes[] length, LightTree::node_count(); 0: empty tree
  // sst: eps = distance_floor * LightTree::length_scale (the float product the CPU forms).
  float sst_eps;
  uint sst_substitutes;  // SstParams::substitutes
  // Block cuts (rtslc, hybrid): BlockCuts::grid and max_size.
  uint cut_block_size;
  uint cut_blocks_x;
  uint cut_blocks_y;
  uint cut_max_size;
  // rtslc
  uint rtslc_interleave;   // r
  uint rtslc_weights;      // ML_RTSLC_WEIGHTS_*
  uint rtslc_frame_index;  // interleaving offset
  // hybrid
  uint hybrid_cut_size;       // HybridParams::cut_size: traversals per sample
  float hybrid_n_min;         // HybridParams::n_min
  float hybrid_d_max;         // HybridParams::d_max: a fraction of the shading point's camera distance
  uint hybrid_mock_cut_size;  // ml_mock_cut[] length
  // rtslc with direct_light = cuts: per block a cut of the emitter tree (core/lights/
  // light_layout.h's light_tree[]) of at most this many nodes, stored after the VPL cuts:
  // block b's nodes at ml_cut_nodes[rtslc_direct_cut_first + b rtslc_direct_cut_max_size ..],
  // its size at ml_cut_sizes[rtslc_direct_sizes_first + b]. 0: the direct light is trace_path's.
  uint rtslc_direct_cut_max_size;
  uint rtslc_direct_cut_first;
  uint rtslc_direct_sizes_first;
  float clamp_per_depth;  // VplLighting::clamp_per_depth
  float substitute_max_extent;  // sst, hybrid: LightTreeParams::substitute_max_extent
  float node_distance_floor;    // slc, sst, rtslc, hybrid walks: LightTreeParams::node_distance_floor
};

SST_END

#ifdef __cplusplus
#include <cstddef>
namespace sst {
static_assert(sizeof(GpuVpl) == 48);
static_assert(offsetof(GpuVpl, position) == 0 && offsetof(GpuVpl, normal) == 16 &&
              offsetof(GpuVpl, intensity) == 32);
static_assert(sizeof(CutGuide) == 32);
static_assert(offsetof(CutGuide, valid) == 12 && offsetof(CutGuide, n) == 16);
static_assert(sizeof(SamplerParams) == 100);
static_assert(offsetof(SamplerParams, sst_eps) == 24 && offsetof(SamplerParams, cut_block_size) == 32 &&
              offsetof(SamplerParams, rtslc_interleave) == 48 && offsetof(SamplerParams, hybrid_cut_size) == 60 &&
              offsetof(SamplerParams, hybrid_mock_cut_size) == 72 &&
              offsetof(SamplerParams, rtslc_direct_cut_max_size) == 76 &&
              offsetof(SamplerParams, rtslc_direct_sizes_first) == 84);
inline constexpr uint32_t kManyLightBufferCount = MANY_LIGHT_BUFFER_COUNT;
}  // namespace sst
#else
// Declares the seven many-light buffers, read-only, at bindings first .. first + 6 in the order
// of the list at the top: the order of sst::gpu::GpuManyLightInputs::buffers().
#define MANY_LIGHT_BUFFERS(first)                                                                   \
  layout(std430, binding = (first)) readonly buffer ManyLightParams { SamplerParams ml_params; };     \
  layout(std430, binding = (first) + 1) readonly buffer ManyLightVpls { GpuVpl ml_vpls[]; };          \
  layout(std430, binding = (first) + 2) readonly buffer ManyLightNodes { LightNode ml_nodes[]; };     \
  layout(std430, binding = (first) + 3) readonly buffer ManyLightCutNodes { uint ml_cut_nodes[]; };   \
  layout(std430, binding = (first) + 4) readonly buffer ManyLightCutSizes { uint ml_cut_sizes[]; };   \
  layout(std430, binding = (first) + 5) readonly buffer ManyLightCutGuides { CutGuide ml_cut_guides[]; }; \
  layout(std430, binding = (first) + 6) readonly buffer ManyLightMockCut { uint ml_mock_cut[]; };
#endif

#endif  // SST_CORE_MANYLIGHT_MANY_LIGHT_LAYOUT_H
