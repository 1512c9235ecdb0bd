#include "core/manylight/rtslc_sampler.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "core/lighttree/box_bounds.h"
#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/gpu_sampler_inputs.h"
#include "core/manylight/slc_sampler.h"
#include "core/rng/hash_rng.h"
#include "core/util/error.h"

namespace sst {

void validate(const RtslcParams& p) {
  validate(p.common.tree);
  if (p.common.tree.tree != "perfect")
    throw Error("rtslc: parameter 'tree' must be 'perfect' (RTSLC's heap-layout tree), got '" + p.common.tree.tree + "'");
  if (p.block_size < 1) throw Error("rtslc: parameter 'block_size' must be >= 1");
  if (p.cut_size < 1 || p.cut_size > 32) throw Error("rtslc: parameter 'cut_size' must be in 1..32");
  if (p.interleave != 1 && p.interleave != 2 && p.interleave != 4)
    throw Error("rtslc: parameter 'interleave' must be 1, 2 or 4");
  parse_rtslc_weights(p.weights);
}

RtslcWeights parse_rtslc_weights(const std::string& name) {
  if (name == "rtslc") return RtslcWeights::rtslc;
  if (name == "slc") return RtslcWeights::slc;
  throw Error("rtslc: parameter 'weights' must be 'rtslc' (Lin & Yuksel 2020) or 'slc' (Yuksel 2019), got '" + name + "'");
}

namespace {

float importance(const LightNode& c, vec3 x, vec3 n) {
  return c.empty() ? 0.0f : luminance(c.intensity) * box_cos_bound_linear(c.bounds(), x, n);
}

// d1^2 IG0 / (d1^2 IG0 + d0^2 IG1); NaN when the denominator is 0 (the caller falls back).
float distance_weight(float ig0, float ig1, float d0, float d1) {
  float a = d1 * ig0, den = a + d0 * ig1;
  return den > 0.0f ? a / den : NAN;
}

// (P_0, P_1) at an internal node; both 0 for a dead branch, where no VPL below can light x.
std::pair<float, float> child_probabilities(const LightTree& tree, const LightNode& node, vec3 x, vec3 n,
                                            RtslcWeights weights) {
  const LightNode &c0 = tree[node.left], &c1 = tree[node.right];
  if (weights == RtslcWeights::slc) {
    // Yuksel 2019, exactly as the slc method weighs them (dead: a zero or non-finite sum).
    std::array<double, 2> w = slc_child_weights(c0, c1, x, n);
    double sum = w[0] + w[1];
    if (!(sum > 0.0) || !std::isfinite(sum)) return {0.0f, 0.0f};
    // P_1 = 1 - P_0 as below: rtslc_traverse takes c0 iff u < P_0, so that is P_1 exactly.
    float p0 = float(w[0] / sum);
    return {p0, 1.0f - p0};
  }
  if (!(importance(c0, x, n) + importance(c1, x, n) > 0.0f)) return {0.0f, 0.0f};
  float p0 = rtslc_child_probability(c0, c1, x, n);
  return {p0, 1.0f - p0};
}

}  // namespace

float rtslc_child_probability(const LightNode& c0, const LightNode& c1, vec3 x, vec3 n) {
  if (c0.empty()) return 0.0f;
  if (c1.empty()) return 1.0f;
  float ig0 = importance(c0, x, n), ig1 = importance(c1, x, n);
  if (!(ig0 + ig1 > 0.0f)) return 0.0f;  // dead branch: neither child can light x
  float ratio = ig0 / (ig0 + ig1);
  float dmin0 = box_distance2_min(c0.bounds(), x), dmin1 = box_distance2_min(c1.bounds(), x);
  if (dmin0 == 0.0f && dmin1 == 0.0f) return ratio;  // x in both boxes: distance says nothing
  float wmax = distance_weight(ig0, ig1, dmin0, dmin1);
  float wmin = distance_weight(ig0, ig1, box_distance2_max(c0.bounds(), x), box_distance2_max(c1.bounds(), x));
  // A zero denominator (a zero-distance side with zero importance) carries no distance
  // information: use the importance ratio for that term.
  if (!std::isfinite(wmax)) wmax = ratio;
  if (!std::isfinite(wmin)) wmin = ratio;
  return std::clamp(0.5f * (wmax + wmin), 0.0f, 1.0f);
}

TreeSample rtslc_traverse(const LightTree& tree, uint32_t from, vec3 x, vec3 n, PixelSampler& sampler,
                          RtslcWeights weights) {
  TreeSample s;
  uint32_t i = from;
  float prob = 1.0f;
  for (;;) {
    ++s.nodes_visited;
    const LightNode& node = tree[i];
    if (node.is_leaf()) break;
    auto [p0, p1] = child_probabilities(tree, node, x, n, weights);
    if (!(p0 + p1 > 0.0f)) return s;  // dead branch: no estimate, no shadow ray
    float u = pixel_sampler_get1d(sampler);
    bool left = u < p0;
    prob *= left ? p0 : p1;
    i = left ? node.left : node.right;
  }
  if (!(prob > 0.0f) || tree[i].empty()) return s;
  s.node = i;
  s.probability = prob;
  return s;
}

double rtslc_leaf_probability(const LightTree& tree, uint32_t from, uint32_t leaf, vec3 x, vec3 n,
                              RtslcWeights weights) {
  double prob = 1.0;
  uint32_t i = leaf;
  while (i > from) {
    uint32_t parent = i / 2;
    const LightNode& p = tree[parent];
    auto [p0, p1] = child_probabilities(tree, p, x, n, weights);
    prob *= (i == p.left) ? double(p0) : double(p1);
    i = parent;
  }
  return i == from ? prob : 0.0;
}

float rtslc_cut_error(const LightNode& node, vec3 x, vec3 n, float min_distance) {
  if (node.empty()) return 0.0f;
  float d2 = std::max(box_distance2_min(node.bounds(), x), min_distance * min_distance);
  return luminance(node.intensity) * box_cos_bound_linear(node.bounds(), x, n) / d2;
}

RtslcSampler::RtslcSampler(const RtslcParams& params) : TreeSamplerBase(params.common.tree), params_(params) {
  validate(params_);
  weights_ = parse_rtslc_weights(params_.weights);
}

void RtslcSampler::prepare(const ManyLightFrame& frame, StageTimer& timer, nlohmann::json& counters) {
  const RenderContext& ctx = frame.context;
  TreeSamplerBase::prepare(frame, timer, counters);
  // RTSLC bounds the distance below at 0.001 of the scene size so that a node touching the
  // pivot does not take every split.
  const float min_distance = 0.001f * ctx.scene.bounds.diagonal();
  auto random_pivot = [&](const BlockRect& r) {
    HashRng rng = hash_rng(ctx.options.seed, uint32_t(r.index), 0, 0x52544C43u);  // "RTLC": the pivot stream
    int px = r.x0 + std::min(int(hash_rng_next(rng) * float(r.w)), r.w - 1);
    int py = r.y0 + std::min(int(hash_rng_next(rng) * float(r.h)), r.h - 1);
    return glm::ivec2(px, py);
  };
  auto error = [&](const LightNode& node, const GBufferSample& g) {
    // No pivot surface (a background pixel): split by intensity alone.
    return g.valid ? rtslc_cut_error(node, g.p, g.n, min_distance) : luminance(node.intensity);
  };
  timer.time("cuts", [&] {
    cuts_ = build_block_cuts(ctx, tree_, params_.block_size, uint32_t(params_.cut_size), random_pivot, error);
  });
  counters["rtslc"] = {{"tree_nodes", tree_.nodes.size()},
                       {"tree_height", tree_.empty() ? 0 : tree_height(tree_)},
                       {"blocks", cuts_.grid.count()},
                       {"mean_cut_size", cuts_.mean_size()}};
}

IndirectEstimate RtslcSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                        PixelSampler& sampler) const {
  IndirectEstimate e;
  if (tree_.empty()) return e;
  const uint32_t r = uint32_t(params_.interleave), slots = r * r;
  const uint32_t slot = (r * (uint32_t(point.y) % r) + uint32_t(point.x) % r + frame_index_) % slots;
  std::span<const uint32_t> cut = cuts_.cut(cuts_.grid.index(point.x, point.y));
  for (uint32_t i = slot; i < cut.size(); i += slots) {
    TreeSample s = rtslc_traverse(tree_, cut[i], point.p, point.basis.n, sampler, weights_);
    e.nodes_visited += s.nodes_visited;
    if (s.node == kNoNode) continue;
    const Vpl& vpl = frame.vpls[tree_[s.node].vpl()];
    e.value += shade_vpl(frame, point, vpl, &e.shadow_rays) * (float(slots) / s.probability);
  }
  return e;
}

void RtslcSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_RTSLC, out);
  set_tree_inputs(tree_, out);
  set_cut_inputs(cuts_, out);
  out.params.rtslc_interleave = uint32_t(params_.interleave);
  out.params.rtslc_weights = weights_ == RtslcWeights::slc ? ML_RTSLC_WEIGHTS_SLC : ML_RTSLC_WEIGHTS_RTSLC;
  out.params.rtslc_frame_index = frame_index_;
}

}  // namespace sst
