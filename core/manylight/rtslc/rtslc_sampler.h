// `rtslc`: Real-Time Stochastic Lightcuts (Lin & Yuksel 2020; docs/design/methods.md). A perfect light
// tree; per k x k pixel block a cut of M nodes built at a random pivot pixel; every pixel
// traverses once from each cut node to a leaf (stochastic lightcuts) and sums the M one-VPL
// estimates, each divided by its traversal probability. Unbiased (without interleaving, per
// pixel; with interleaving, over each r x r tile of pixels).
//
// With direct_light = cuts the direct light comes from per-block cuts of the scene's emitter tree
// too (rtslc_direct.h: the paper's real-light case), not from trace_path's one light sample.
//
// Parameters: RtslcParams below, which holds those of VPL generation and the light tree (which
// must be the perfect one).
#pragma once
#include <span>
#include <string>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/manylight/block_cuts.h"
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/rtslc/rtslc_estimate.h"
#include "core/pt/path_tracer.h"
// After path_tracer.h, which binds the scene's, the lights' and the rays' hooks.
#include "core/manylight/rtslc/rtslc_direct.h"
#include "core/manylight/tree_sampler_base.h"
#include "core/manylight/tree_method_params.h"

namespace sst {

struct RtslcParams {
  TreeMethodParams tree_method{kNodeFloorAboveForCuts};
  int block_size = 8;
  int cut_size = 8;
  int interleave = 1;
  std::string weights = "rtslc";
  std::string direct_light = "sampler";
  int direct_cut_size = 8;

  RtslcParams() { tree_method.tree.tree = "perfect"; }  // the paper's tree; the only one allowed
  template <class V>
  void visit(V&& v) {
    tree_method.visit(v);
    v("block_size", block_size, "k: pixels per side of a block; one light cut per block, built at a random pixel of it");
    v("cut_size", cut_size, "M: nodes per light cut (1..32); one traversal from each per indirect sample");
    v("interleave", interleave,
      "interleaved sampling rate r (1, 2 or 4): pixel s of an r x r tile evaluates the cut nodes i with i mod r^2 = "
      "(s + frame) mod r^2, weighted by r^2 (unbiased over the tile, not per pixel; across frames each pixel takes "
      "every slot in turn, as the paper interleaves over time)");
    v("weights", weights,
      "traversal weights: rtslc (Lin & Yuksel 2020: mean of the min- and max-distance weights) or slc (Yuksel 2019: "
      "min distance, as the slc method; for equal-sample comparisons)");
    v("direct_light", direct_light,
      "sampler: direct light as every method takes it (one light sample by --light-sampler, MIS with the BRDF); "
      "cuts: RTSLC on the scene's own emitters, a cut of the emitter tree per block at the same pivot, one light "
      "sample down from each cut node (interleaved as above), no MIS; needs --light-sampler tree or slc, whose "
      "child weights the walks below the cut use");
    v("direct_cut_size", direct_cut_size,
      "direct_light = cuts: nodes per cut of the emitter tree (1..32; every directional light is one more)");
  }
};
void validate(const RtslcParams& params);  // sst::Error naming the bad parameter

// The traversal weights below a cut node (parameter `weights`). The cut-building error
// (rtslc_cut_error) is the same for both.
enum class RtslcWeights {
  rtslc,  // rtslc_child_probability (rtslc_estimate.h): the mean of the min- and max-distance weights
  slc,    // P_0 = w_0 / (w_0 + w_1) with Yuksel 2019's slc_child_weights (slc_estimate.h)
};
// "rtslc" or "slc"; anything else is an sst::Error naming parameter 'weights' and the allowed values.
RtslcWeights parse_rtslc_weights(const std::string& name);

// rtslc_traverse (rtslc_estimate.h) on `tree` alone, outside a frame: one stochastic descent
// from `from` to a leaf with `weights` and node-distance floor `floor_fraction`. For tests.
RtslcSample rtslc_traverse(const LightTree& tree, uint32_t from, vec3 x, vec3 n, PixelSampler& sampler,
                           RtslcWeights weights = RtslcWeights::rtslc, float floor_fraction = 0.0f);
// The exact probability that rtslc_traverse from `from` (with the same `weights`) ends at `leaf`
// (0 if not below it). Heap layout only (perfect tree).
double rtslc_leaf_probability(const LightTree& tree, uint32_t from, uint32_t leaf, vec3 x, vec3 n,
                              RtslcWeights weights = RtslcWeights::rtslc, float floor_fraction = 0.0f);

class RtslcSampler final : public TreeSamplerBase {
 public:
  explicit RtslcSampler(const RtslcParams& params);
  const BlockCuts& cuts() const { return cuts_; }
  // flatten: every helper of the walk inlined whatever GCC's size budget says; without it, when
  // the shared kernels grew, GCC left some of them calls per node (measured: sampling 8% slower).
  [[gnu::flatten]] IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_rtslc(inputs(), point, sampler);
  }
  vec3 estimate_direct(const RenderContext& ctx, const ShadingPoint& point, PixelSampler& sampler,
                       RayCounters& counters) const override;

 protected:
  uint32_t method_id() const override { return ML_METHOD_rtslc; }
  void build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) override;

 private:
  // direct_light = cuts: each block's cut of the emitter tree at cuts_' pivot, after the VPL cuts.
  void build_direct_cuts(const RenderContext& ctx, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs);

  RtslcParams params_;
  RtslcWeights weights_ = RtslcWeights::rtslc;  // params_.weights, parsed
  BlockCuts cuts_;  // built at each block's random pivot pixel
  // direct_light = cuts: the cuts as the estimators read them, cuts_' nodes and sizes followed by
  // those of the emitter-tree cuts (otherwise the estimators read cuts_ itself).
  std::vector<uint32_t> cut_nodes_, cut_sizes_;
};

}  // namespace sst
