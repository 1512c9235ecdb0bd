// `hybrid`: shallow light cuts over a stochastic substitute tree (the hybrid thesis, ch. 5;
// docs/design/methods.md). A perfect light tree with SST substitutes. Per k x k block a shallow cut of n
// nodes is built at the block centre's G-buffer point by splitting the node of largest expected
// contribution lum(I) G_avg / d^2. Each pixel blends the four nearest blocks' cuts index by
// index (Algorithm 1): for cut index i it picks one of the four cuts with probability
// proportional to bilinear weight x geometric similarity, and traverses from that cut's node i
// with the same expected-contribution weights, stopping at a suitable SST node (sampled from its
// Gaussian and shaded as a point light with the node's summed intensity) or a leaf. When all four
// blocks are dissimilar it evaluates the mock cut: every node of tree level floor(log2 n).
//
// Weighting: each traversal's estimate is divided by the probability of the path from the
// chosen cut node, so it is unbiased for that node's subtree (substitutes aside). The blend is
// NOT unbiased: node i of one cut and node i of its neighbour cover different VPLs, so a pixel's
// n nodes need not partition the VPLs (some are counted twice, some never). The thesis accepts
// this bias for smooth block transitions, and so do we; together with the substitutes and the
// expected-contribution weights (zero for a box entirely behind x but not a bound) the method is
// biased by design.
//
// Parameters: HybridParams below, which holds those of VPL generation and of the light tree, with
// the thesis's tree and thresholds as defaults (its constructor).
// The estimate and the expected contribution hybrid_weight are hybrid_estimate.h's.
#pragma once
#include <span>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/block_cuts.h"
#include "core/manylight/hybrid/hybrid_estimate.h"
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/tree_sampler_base.h"
#include "core/manylight/tree_method_params.h"

namespace sst {

struct HybridParams {
  TreeMethodParams tree_method{kNodeFloorAboveForCuts};
  int block_size = 8;
  int cut_size = 8;
  // The thesis gives no values for n_min and d_max; 0.9 (~25 degrees) and a quarter of the point's
  // camera distance are ours (d_max was 5% of the scene diagonal, which a ground plane or sky
  // around the view inflates: docs/design/lengths.md).
  float n_min = 0.9f;
  float d_max = 0.25f;

  HybridParams() {
    tree_method.tree.tree = "perfect";
    tree_method.tree.v_min = 0.7f;       // thesis eq. 5.6
    tree_method.tree.sigma_max = 0.015f;  // thesis 0.3 in its scene units (light_tree.h)
  }
  template <class V>
  void visit(V&& v) {
    tree_method.visit(v);
    v("block_size", block_size, "k: pixels per side of a block; one shallow light cut per block");
    v("cut_size", cut_size, "n: nodes per cut (1..32) = traversals per indirect sample, the per-pixel budget");
    v("n_min", n_min,
      "cut blending: a neighbouring block's cut is used only if the dot product of its centre's normal and the "
      "pixel's is > n_min, the cosine of the largest angle between them");
    v("d_max", d_max,
      "cut blending: a neighbouring block's cut is used only if also its centre's point is closer to the pixel's than d_max x the pixel's distance to the camera; with no "
      "similar block the pixel takes the mock cut (every node of tree level floor(log2 n))");
  }
};
void validate(const HybridParams& params);  // sst::Error naming the bad parameter

class HybridSampler final : public TreeSamplerBase {
 public:
  explicit HybridSampler(const HybridParams& params);
  const BlockCuts& cuts() const { return cuts_; }
  std::span<const uint32_t> mock_cut() const { return mock_cut_; }
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_hybrid(inputs(), point, sampler);
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_hybrid; }
  void build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) override;

 private:
  HybridParams params_;
  BlockCuts cuts_;  // built at each block's centre pixel, each cut in leaf order
  std::vector<uint32_t> mock_cut_;
};

}  // namespace sst
