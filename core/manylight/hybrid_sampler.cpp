#include "core/manylight/hybrid_sampler.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/lighttree/box_bounds.h"
#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/gpu_sampler_inputs.h"
#include "core/util/error.h"

namespace sst {

void validate(const HybridParams& p) {
  validate(p.common.tree);
  if (p.common.tree.tree != "perfect")
    throw Error("hybrid: parameter 'tree' must be 'perfect' (mock cuts use its heap levels), got '" + p.common.tree.tree + "'");
  if (p.block_size < 1) throw Error("hybrid: parameter 'block_size' must be >= 1");
  if (p.cut_size < 1 || p.cut_size > 32) throw Error("hybrid: parameter 'cut_size' must be in 1..32");
  if (!(p.n_min >= -1.0f && p.n_min <= 1.0f)) throw Error("hybrid: parameter 'n_min' must be in [-1, 1]");
  if (!(p.d_max > 0.0f) || !std::isfinite(p.d_max)) throw Error("hybrid: parameter 'd_max' must be > 0");
}

float hybrid_weight(const LightNode& node, vec3 x, vec3 n, float clamp_distance) {
  if (node.empty()) return 0.0f;
  float g = 0.0f;
  for (int c = 0; c < 8; ++c) {
    vec3 corner((c & 1) ? node.bounds_hi.x : node.bounds_lo.x, (c & 2) ? node.bounds_hi.y : node.bounds_lo.y,
                (c & 4) ? node.bounds_hi.z : node.bounds_lo.z);
    vec3 d = corner - x;
    float len = glm::length(d);
    if (len > 0.0f) g += std::max(glm::dot(n, d) / len, 0.0f);
  }
  float d2 = std::max(box_distance2_min(node.bounds(), x), clamp_distance * clamp_distance);
  float w = luminance(node.intensity) * (g * 0.125f) / d2;
  return std::isfinite(w) ? w : 0.0f;
}

namespace {

uint32_t level_of(uint32_t node) { return uint32_t(std::bit_width(node)) - 1u; }

// The first leaf below a heap node: sorting a cut by it orders the nodes left to right, so that
// index i of neighbouring blocks' cuts tends to cover the same part of the tree (the blend pairs
// nodes by index).
uint32_t first_leaf_below(const LightTree& tree, uint32_t node) {
  return node << (level_of(tree.first_leaf) - level_of(node));
}

// Two standard normal deviates (Box-Muller).
vec2 normal_pair(PixelSampler& sampler) {
  vec2 u = pixel_sampler_get2d(sampler);
  float r = std::sqrt(-2.0f * std::log(1.0f - u.x));  // u.x < 1: finite
  float phi = 2.0f * float(M_PI) * u.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}

// A point light drawn from a suitable node's substitute distribution (as SST): the mean plus
// normal deviates scaled by the standard deviations in the node's local frame, clamped into its
// box, carrying the node's summed intensity and normal.
Vpl sample_substitute(const LightNode& node, PixelSampler& sampler) {
  vec2 a = normal_pair(sampler), b = normal_pair(sampler);
  vec3 sd = glm::sqrt(glm::max(node.variance, vec3(0.0f)));
  vec3 offset = to_world(basis_from_normal(node.normal), vec3(a.x, a.y, b.x) * sd);
  Vpl v;
  v.position = glm::clamp(node.mean + offset, node.bounds_lo, node.bounds_hi);
  v.normal = node.normal;
  v.intensity = node.intensity;
  return v;
}

}  // namespace

HybridSampler::HybridSampler(const HybridParams& params) : TreeSamplerBase(params.common.tree), params_(params) { validate(params_); }

void HybridSampler::prepare(const ManyLightFrame& frame, StageTimer& timer, nlohmann::json& counters) {
  const RenderContext& ctx = frame.context;
  TreeSamplerBase::prepare(frame, timer, counters);
  const uint32_t n = uint32_t(params_.cut_size);
  d_max_abs_ = params_.d_max * ctx.scene.bounds.diagonal();
  const float clamp = frame.clamp_distance;
  auto centre = [](const BlockRect& r) { return glm::ivec2(r.x0 + r.w / 2, r.y0 + r.h / 2); };
  auto error = [&](const LightNode& node, const GBufferSample& g) {
    return g.valid ? hybrid_weight(node, g.p, g.n, clamp) : luminance(node.intensity);
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
  counters["hybrid"] = {{"tree_nodes", tree_.nodes.size()},
                        {"tree_height", tree_.empty() ? 0 : tree_height(tree_)},
                        {"suitable_internal_nodes", count_suitable_internal(tree_)},
                        {"blocks", cuts_.grid.count()},
                        {"mock_cut_size", mock_cut_.size()}};
}

void HybridSampler::traverse(const ManyLightFrame& frame, const ShadingPoint& point, uint32_t from,
                             PixelSampler& sampler, IndirectEstimate& e) const {
  uint32_t i = from;
  float prob = 1.0f;
  for (;;) {
    ++e.nodes_visited;
    const LightNode& node = tree_[i];
    if (node.empty()) return;
    if (node.is_leaf()) {
      e.value += shade_vpl(frame, point, frame.vpls[node.vpl()], &e.shadow_rays) / prob;
      return;
    }
    if (node.suitable()) {  // close enough to a flat patch: sample its substitute
      e.value += shade_vpl(frame, point, sample_substitute(node, sampler), &e.shadow_rays) / prob;
      return;
    }
    float w0 = hybrid_weight(tree_[node.left], point.p, point.basis.n, frame.clamp_distance);
    float w1 = hybrid_weight(tree_[node.right], point.p, point.basis.n, frame.clamp_distance);
    if (!(w0 + w1 > 0.0f)) return;  // neither child is expected to contribute: no backtracking
    float p0 = w0 / (w0 + w1);
    bool left = pixel_sampler_get1d(sampler) < p0;
    prob *= left ? p0 : 1.0f - p0;
    i = left ? node.left : node.right;
  }
}

IndirectEstimate HybridSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                         PixelSampler& sampler) const {
  IndirectEstimate e;
  if (tree_.empty()) return e;
  // The four block centres around the pixel and their bilinear weights (clamped at the border,
  // where a block may appear twice).
  const float k = float(params_.block_size);
  float fx = (float(point.x) + 0.5f) / k - 0.5f, fy = (float(point.y) + 0.5f) / k - 0.5f;
  int bx = int(std::floor(fx)), by = int(std::floor(fy));
  float tx = fx - float(bx), ty = fy - float(by);
  size_t blocks[4];
  float p[4], sum = 0.0f;
  for (int c = 0; c < 4; ++c) {
    int cx = std::clamp(bx + (c & 1), 0, cuts_.grid.blocks_x - 1);
    int cy = std::clamp(by + (c >> 1), 0, cuts_.grid.blocks_y - 1);
    blocks[c] = size_t(cy) * size_t(cuts_.grid.blocks_x) + size_t(cx);
    const GBufferSample& g = cuts_.guides[blocks[c]];
    bool similar = g.valid && glm::dot(g.n, point.basis.n) > params_.n_min && glm::distance(g.p, point.p) < d_max_abs_;
    p[c] = similar ? ((c & 1) ? tx : 1.0f - tx) * ((c >> 1) ? ty : 1.0f - ty) : 0.0f;
    sum += p[c];
  }
  if (!(sum > 0.0f)) {  // no similar block: the mock cut
    for (uint32_t node : mock_cut_) traverse(frame, point, node, sampler, e);
    return e;
  }
  for (uint32_t i = 0; i < uint32_t(params_.cut_size); ++i) {
    float u = pixel_sampler_get1d(sampler) * sum;
    int c = 0;
    while (c < 3 && (u >= p[c] || p[c] == 0.0f)) {
      u -= p[c];
      ++c;
    }
    if (p[c] == 0.0f) c = int(std::max_element(p, p + 4) - p);  // rounding past the last weight
    std::span<const uint32_t> cut = cuts_.cut(blocks[c]);
    if (i < cut.size()) traverse(frame, point, cut[i], sampler, e);
  }
  return e;
}

void HybridSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_HYBRID, out);
  set_tree_inputs(tree_, out);
  set_cut_inputs(cuts_, out);
  out.mock_cut = mock_cut_;
  out.params.hybrid_cut_size = uint32_t(params_.cut_size);
  out.params.hybrid_n_min = params_.n_min;
  out.params.hybrid_d_max_abs = d_max_abs_;
  out.params.hybrid_mock_cut_size = uint32_t(mock_cut_.size());
}

}  // namespace sst
