// What a many-light sampler hands to the Vulkan backend after prepare(): the GPU twin of its
// state (core/manylight/many_light_layout.h). The tree and the per-block cuts stay built on the CPU
// by the existing code; the GPU only evaluates estimate() per shading point
// (gpu/shaders/indirect_sampler.glsl). Plain C++: no Vulkan needed to fill it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/block_cuts.h"
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/many_light_layout.h"

namespace sst {

// The GLSL LightNode is declared field for field from sst::LightNode: the node array is uploaded
// as is, so the two layouts must agree byte for byte.
static_assert(sizeof(glsl::LightNode) == sizeof(LightNode));
static_assert(offsetof(glsl::LightNode, bounds_lo) == offsetof(LightNode, bounds_lo) &&
              offsetof(glsl::LightNode, left) == offsetof(LightNode, left) &&
              offsetof(glsl::LightNode, bounds_hi) == offsetof(LightNode, bounds_hi) &&
              offsetof(glsl::LightNode, right) == offsetof(LightNode, right) &&
              offsetof(glsl::LightNode, intensity) == offsetof(LightNode, intensity) &&
              offsetof(glsl::LightNode, vpl_count) == offsetof(LightNode, vpl_count) &&
              offsetof(glsl::LightNode, mean) == offsetof(LightNode, mean) &&
              offsetof(glsl::LightNode, similarity) == offsetof(LightNode, similarity) &&
              offsetof(glsl::LightNode, normal) == offsetof(LightNode, normal) &&
              offsetof(glsl::LightNode, sigma_z) == offsetof(LightNode, sigma_z) &&
              offsetof(glsl::LightNode, variance) == offsetof(LightNode, variance) &&
              offsetof(glsl::LightNode, flags) == offsetof(LightNode, flags));
static_assert(LightNode::kLeaf == ML_NODE_LEAF && LightNode::kSuitable == ML_NODE_SUITABLE && kNoNode == ML_NO_NODE);

// Filled by IndirectSampler::gpu_inputs. The spans point into the sampler and stay valid until
// its next prepare(); guides are converted to the GPU layout and owned here. Empty spans for
// what a method does not use.
struct GpuSamplerInputs {
  glsl::SamplerParams params{};
  std::span<const LightNode> nodes;
  std::span<const uint32_t> cut_nodes;
  std::span<const uint32_t> cut_sizes;
  std::vector<glsl::CutGuide> guides;
  std::span<const uint32_t> mock_cut;
};

// Starts `out` afresh for `method` (ML_METHOD_*) with the frame-wide parameters.
inline void begin_gpu_inputs(const ManyLightFrame& frame, uint32_t method, GpuSamplerInputs& out) {
  out = {};
  out.params.method = method;
  out.params.vpl_count = uint32_t(frame.vpls.size());
  out.params.clamp_distance = frame.clamp_distance;
  out.params.tree_root = kNoNode;
}

// The tree's nodes and where its root and leaves are.
inline void set_tree_inputs(const LightTree& tree, GpuSamplerInputs& out) {
  out.nodes = tree.nodes;
  out.params.tree_root = tree.empty() ? kNoNode : tree.root;
  out.params.tree_first_leaf = tree.first_leaf;
  out.params.tree_node_count = uint32_t(tree.nodes.size());
}

// The per-block cuts and their guides (rtslc, hybrid).
inline void set_cut_inputs(const BlockCuts& cuts, GpuSamplerInputs& out) {
  out.cut_nodes = cuts.nodes;
  out.cut_sizes = cuts.sizes;
  out.params.cut_block_size = uint32_t(cuts.grid.block_size);
  out.params.cut_blocks_x = uint32_t(cuts.grid.blocks_x);
  out.params.cut_blocks_y = uint32_t(cuts.grid.blocks_y);
  out.params.cut_max_size = cuts.max_size;
  out.guides.resize(cuts.guides.size());
  for (size_t i = 0; i < cuts.guides.size(); ++i) {
    const GBufferSample& g = cuts.guides[i];
    out.guides[i] = {g.p, g.valid ? 1u : 0u, g.n, 0.0f};
  }
}

}  // namespace sst
