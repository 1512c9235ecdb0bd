// The many-light samplers' inputs as they cross the host/GPU boundary, defined once for
// C++ (namespace sst::glsl, static_asserts) and GLSL: the VPLs, the light tree's nodes (the very
// bytes of sst::LightNode, core/lighttree/light_tree.h), the per-block cuts of rtslc and the
// hybrid with the G-buffer samples they were built for, the hybrid's mock cut, and one
// SamplerParams saying which sampler runs and with what. The CPU builds all of it in
// IndirectSampler::prepare and hands it over through IndirectSampler::gpu_inputs
// (core/manylight/gpu_sampler_inputs.h); gpu/many_light_upload.h uploads it;
// gpu/shaders/indirect_sampler.glsl reads it.
//
// Buffers, std430, in the order of MANY_LIGHT_BUFFERS(first) (and GpuManyLightInputs::buffers()):
//   first + 0  SamplerParams ml_params        one element
//   first + 1  GpuVpl        ml_vpls[]        VplSet, index for index
//   first + 2  LightNode     ml_nodes[]       LightTree::nodes, index for index
//   first + 3  uint          ml_cut_nodes[]   BlockCuts::nodes (block b: [b max_size, +sizes[b]))
//   first + 4  uint          ml_cut_sizes[]   BlockCuts::sizes
//   first + 5  CutGuide      ml_cut_guides[]  BlockCuts::guides
//   first + 6  uint          ml_mock_cut[]    HybridSampler::mock_cut()
// Arrays a sampler does not use are bound as 16-byte dummies and never read.
#ifndef SST_CORE_MANYLIGHT_MANY_LIGHT_LAYOUT_H
#define SST_CORE_MANYLIGHT_MANY_LIGHT_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

#define MANY_LIGHT_BUFFER_COUNT 7

// SamplerParams.method: which IndirectSampler estimate_indirect runs.
#define ML_METHOD_EXHAUSTIVE 0u
#define ML_METHOD_UNIFORM 1u
#define ML_METHOD_SLC 2u
#define ML_METHOD_SST 3u
#define ML_METHOD_RTSLC 4u
#define ML_METHOD_HYBRID 5u

// SamplerParams.rtslc_weights (sst::RtslcWeights).
#define ML_RTSLC_WEIGHTS_RTSLC 0u
#define ML_RTSLC_WEIGHTS_SLC 1u

// LightNode.flags (LightNode::kLeaf, LightNode::kSuitable) and "no node / no VPL" (kNoNode).
#define ML_NODE_LEAF 1u
#define ML_NODE_SUITABLE 2u
#define ML_NO_NODE 0xFFFFFFFFu

// One VPL (sst::Vpl), each vec3 padded to 16 bytes.
struct GpuVpl {
  vec3 position;
  float pad0;
  vec3 normal;  // unit
  float pad1;
  vec3 intensity;
  float pad2;
};

// sst::LightNode field for field (see light_tree.h for the meaning of each): six rows of a vec3
// and a 4-byte scalar, which std430 packs like the C++ struct. Leaves: left = VPL index
// (ML_NO_NODE for padding), right = ML_NO_NODE.
struct LightNode {
  vec3 bounds_lo;
  uint left;
  vec3 bounds_hi;
  uint right;
  vec3 intensity;
  uint vpl_count;
  vec3 mean;
  float similarity;
  vec3 normal;
  float sigma_z;
  vec3 variance;
  uint flags;
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
  uint method;           // ML_METHOD_*
  uint vpl_count;        // ml_vpls[] length
  float clamp_distance;  // ManyLightFrame::clamp_distance
  uint tree_root;        // LightTree::root (tree samplers); ML_NO_NODE for an empty tree
  uint tree_first_leaf;  // LightTree::first_leaf
  uint tree_node_count;  // ml_nodes[] length; 0: empty tree
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
  float hybrid_d_max_abs;     // d_max * scene diagonal
  uint hybrid_mock_cut_size;  // ml_mock_cut[] length
  uint pad0;
};

#ifdef __cplusplus
static_assert(sizeof(GpuVpl) == 48);
static_assert(offsetof(GpuVpl, position) == 0 && offsetof(GpuVpl, normal) == 16 &&
              offsetof(GpuVpl, intensity) == 32);
static_assert(sizeof(LightNode) == 96);
static_assert(offsetof(LightNode, left) == 12 && offsetof(LightNode, bounds_hi) == 16 &&
              offsetof(LightNode, right) == 28 && offsetof(LightNode, intensity) == 32 &&
              offsetof(LightNode, vpl_count) == 44 && offsetof(LightNode, mean) == 48 &&
              offsetof(LightNode, similarity) == 60 && offsetof(LightNode, normal) == 64 &&
              offsetof(LightNode, sigma_z) == 76 && offsetof(LightNode, variance) == 80 &&
              offsetof(LightNode, flags) == 92);
static_assert(sizeof(CutGuide) == 32);
static_assert(offsetof(CutGuide, valid) == 12 && offsetof(CutGuide, n) == 16);
static_assert(sizeof(SamplerParams) == 80);
static_assert(offsetof(SamplerParams, sst_eps) == 24 && offsetof(SamplerParams, cut_block_size) == 32 &&
              offsetof(SamplerParams, rtslc_interleave) == 48 && offsetof(SamplerParams, hybrid_cut_size) == 60 &&
              offsetof(SamplerParams, hybrid_mock_cut_size) == 72);
inline constexpr uint32_t kManyLightBufferCount = MANY_LIGHT_BUFFER_COUNT;
}  // namespace sst::glsl
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
