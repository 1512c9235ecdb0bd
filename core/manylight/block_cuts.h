// Shared machinery of the per-block light-cut samplers (rtslc, hybrid; docs/design/methods.md): box
// geometry bounds at a shading point, a greedy cut builder, and a per-block G-buffer traced at
// chosen pixels during prepare.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/indirect_sampler.h"

namespace sst {

// A cut: node indices of a tree whose subtrees are disjoint and cover every VPL.
// Greedy top-down build: start with {root}; repeatedly replace the splittable cut node of
// largest priority by its non-empty children until the cut has `max_nodes` nodes or holds only
// leaves. Priority is (error(node), lum(I)) compared lexicographically: nodes of zero error (seen
// from the block's own pixel) are still split, largest intensity first, so that every cut of a
// tree reaches the same size min(max_nodes, vpl_count) (the hybrid blends cuts index by index).
// Leaves are never split. Appends to `cut`.
using NodeError = std::function<float(const LightNode&)>;
void build_cut(const LightTree& tree, uint32_t max_nodes, const NodeError& error, std::vector<uint32_t>& cut);

// The first camera hit through a pixel's centre: the G-buffer entry a block's cut is built for.
struct GBufferSample {
  bool valid = false;  // false: the ray left the scene
  vec3 p{0.0f};
  vec3 n{0.0f};  // shading normal on the viewer's side
  float depth = 0.0f;  // distance from the camera
};
GBufferSample trace_gbuffer(const RenderContext& ctx, int x, int y);

// The k x k block grid over the image.
struct BlockGrid {
  int block_size = 1;
  int blocks_x = 0, blocks_y = 0;
  BlockGrid() = default;
  BlockGrid(int width, int height, int k)
      : block_size(k), blocks_x(blocks_along(width, k)), blocks_y(blocks_along(height, k)) {}
  // ceil(n / k) without forming n + k - 1, which overflows for a block size near INT_MAX.
  static int blocks_along(int n, int k) { return n <= 0 ? 0 : (n - 1) / k + 1; }
  size_t count() const { return size_t(blocks_x) * size_t(blocks_y); }
  size_t index(int x, int y) const { return size_t(y / block_size) * size_t(blocks_x) + size_t(x / block_size); }
};

// A block's pixels, clipped to the image.
struct BlockRect {
  size_t index = 0;
  int x0 = 0, y0 = 0, w = 0, h = 0;
};

// The cut of every block: block b's cut is nodes[b max_size, b max_size + sizes[b]), built for
// the G-buffer sample guides[b].
struct BlockCuts {
  BlockGrid grid;
  uint32_t max_size = 0;
  std::vector<uint32_t> nodes;
  std::vector<uint32_t> sizes;
  std::vector<GBufferSample> guides;
  std::span<const uint32_t> cut(size_t block) const {
    return {nodes.data() + block * size_t(max_size), sizes[block]};
  }
  double mean_size() const;
};

// Builds every block's cut in parallel: traces the G-buffer at the pixel `guide_pixel` picks in
// the block, builds the cut with `error` seen from that sample, then lets `order` (if given)
// reorder it. What differs between rtslc and the hybrid is only these three choices.
using GuidePixel = std::function<glm::ivec2(const BlockRect&)>;
using GuidedError = std::function<float(const LightNode&, const GBufferSample&)>;
using CutOrder = std::function<void(std::vector<uint32_t>&)>;
// The cuts and their guides as the estimators read them (SamplerInputs).
void set_cut_inputs(const BlockCuts& cuts, SamplerInputs& out);

BlockCuts build_block_cuts(const RenderContext& ctx, const LightTree& tree, int block_size, uint32_t max_size,
                           const GuidePixel& guide_pixel, const GuidedError& error, const CutOrder& order = {});

}  // namespace sst
