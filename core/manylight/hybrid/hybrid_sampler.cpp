#include "core/manylight/hybrid/hybrid_sampler.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/math/box_bounds.h"
#include "core/util/error.h"

namespace sst {

void validate(const HybridParams& p) {
  validate(p.tree_method.tree);
  if (p.tree_method.tree.tree != "perfect")
    throw Error("hybrid: parameter 'tree' must be 'perfect' (mock cuts use its heap levels), got '" + p.tree_method.tree.tree + "'");
  if (p.block_size < 1) throw Error("hybrid: parameter 'block_size' must be >= 1");
  if (p.cut_size < 1 || p.cut_size > 32) throw Error("hybrid: parameter 'cut_size' must be in 1..32");
  if (!(p.n_min >= -1.0f && p.n_min <= 1.0f)) throw Error("hybrid: parameter 'n_min' must be in [-1, 1]");
  if (!(p.d_max > 0.0f) || !std::isfinite(p.d_max)) throw Error("hybrid: parameter 'd_max' must be > 0");
}

namespace {

uint32_t level_of(uint32_t node) { return uint32_t(std::bit_width(node)) - 1u; }

// The first leaf below a heap node: sorting a cut by it orders the nodes left to right, so that
// index i of neighbouring blocks' cuts tends to cover the same part of the tree (the blend pairs
// nodes by index).
uint32_t first_leaf_below(const LightTree& tree, uint32_t node) {
  return node << (level_of(tree.first_leaf) - level_of(node));
}

}  // namespace

HybridSampler::HybridSampler(const HybridParams& params) : TreeSamplerBase(params.tree_method.tree), params_(params) { validate(params_); }

void HybridSampler::build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) {
  const RenderContext& ctx = lighting.context;
  TreeSamplerBase::build(lighting, timer, counters, inputs);
  const uint32_t n = uint32_t(params_.cut_size);
  auto centre = [](const BlockRect& r) { return glm::ivec2(r.x0 + r.w / 2, r.y0 + r.h / 2); };
  auto error = [&](const LightNode& node, const GBufferSample& g) {
    return g.valid ? hybrid_weight(node, g.p, g.n, vpl_clamp_at(lighting.clamp_distance, lighting.clamp_per_depth, g.depth),
                                   0.0f)
                   : luminance(node.intensity);
  };
  // Cut i of neighbouring blocks must cover nearby parts of the tree for blending by index.
  auto leaf_order = [&](std::vector<uint32_t>& cut) {
    std::sort(cut.begin(), cut.end(),
              [&](uint32_t a, uint32_t c) { return first_leaf_below(tree_, a) < first_leaf_below(tree_, c); });
  };
  timer.time("cuts", [&] { cuts_ = build_block_cuts(ctx, tree_, params_.block_size, n, centre, error, leaf_order); });
  mock_cut_.clear();
  if (!tree_.empty()) {
    uint32_t level = std::min(level_of(n), level_of(tree_.first_leaf));
    for (uint32_t i = 1u << level; i < (2u << level); ++i)
      if (!tree_[i].empty()) mock_cut_.push_back(i);
  }
  counters["hybrid"] = {{"tree_nodes", tree_.node_count()},
                        {"tree_height", tree_.empty() ? 0 : tree_height(tree_)},
                        {"suitable_internal_nodes", count_suitable_internal(tree_)},
                        {"blocks", cuts_.grid.count()},
                        {"mock_cut_size", mock_cut_.size()}};
  set_cut_inputs(cuts_, inputs);
  inputs.mock_cut = mock_cut_;
  inputs.params.hybrid_cut_size = uint32_t(params_.cut_size);
  inputs.params.hybrid_n_min = params_.n_min;
  inputs.params.hybrid_d_max = params_.d_max;
  inputs.params.hybrid_mock_cut_size = uint32_t(mock_cut_.size());
}

}  // namespace sst
