#include "core/manylight/rtslc/rtslc_sampler.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "core/math/box_bounds.h"
#include "core/rng/hash_rng.h"
#include "core/util/error.h"

namespace sst {

void validate(const RtslcParams& p) {
  validate(p.tree_method.tree);
  if (p.tree_method.tree.tree != "perfect")
    throw Error("rtslc: parameter 'tree' must be 'perfect' (RTSLC's heap-layout tree), got '" + p.tree_method.tree.tree + "'");
  if (p.block_size < 1) throw Error("rtslc: parameter 'block_size' must be >= 1");
  if (p.cut_size < 1 || p.cut_size > 32) throw Error("rtslc: parameter 'cut_size' must be in 1..32");
  if (p.interleave != 1 && p.interleave != 2 && p.interleave != 4)
    throw Error("rtslc: parameter 'interleave' must be 1, 2 or 4");
  parse_rtslc_weights(p.weights);
  if (p.direct_light != "sampler" && p.direct_light != "cuts")
    throw Error("rtslc: parameter 'direct_light' must be 'sampler' or 'cuts', got '" + p.direct_light + "'");
  if (p.direct_cut_size < 1 || p.direct_cut_size > 32) throw Error("rtslc: parameter 'direct_cut_size' must be in 1..32");
}

RtslcWeights parse_rtslc_weights(const std::string& name) {
  if (name == "rtslc") return RtslcWeights::rtslc;
  if (name == "slc") return RtslcWeights::slc;
  throw Error("rtslc: parameter 'weights' must be 'rtslc' (Lin & Yuksel 2020) or 'slc' (Yuksel 2019), got '" + name + "'");
}

namespace {

uint32_t weights_id(RtslcWeights weights) {
  return weights == RtslcWeights::slc ? ML_RTSLC_WEIGHTS_SLC : ML_RTSLC_WEIGHTS_RTSLC;
}

}  // namespace

RtslcSample rtslc_traverse(const LightTree& tree, uint32_t from, vec3 x, vec3 n, PixelSampler& sampler,
                           RtslcWeights weights, float floor_fraction) {
  SamplerInputs inputs;
  set_tree_inputs(tree, inputs);
  inputs.params.rtslc_weights = weights_id(weights);
  inputs.params.node_distance_floor = floor_fraction;
  return rtslc_traverse(inputs, from, x, n, sampler);
}

double rtslc_leaf_probability(const LightTree& tree, uint32_t from, uint32_t leaf, vec3 x, vec3 n,
                              RtslcWeights weights, float floor_fraction) {
  double prob = 1.0;
  uint32_t i = leaf;
  while (i > from) {
    uint32_t parent = i / 2;
    const LightNode& p = tree[parent];
    vec2 pc = rtslc_child_probabilities(tree[p.left], tree[p.right], x, n, weights_id(weights), floor_fraction);
    prob *= (i == p.left) ? double(pc.x) : double(pc.y);
    i = parent;
  }
  return i == from ? prob : 0.0;
}

RtslcSampler::RtslcSampler(const RtslcParams& params) : TreeSamplerBase(params.tree_method.tree), params_(params) {
  validate(params_);
  weights_ = parse_rtslc_weights(params_.weights);
}

void RtslcSampler::build_direct_cuts(const RenderContext& ctx, StageTimer& timer, nlohmann::json& counters,
                                     SamplerInputs& inputs) {
  const LightSamplerKind kind = ctx.lights.kind();
  if (kind != LightSamplerKind::Tree && kind != LightSamplerKind::Slc)
    throw Error(std::string("rtslc: direct_light 'cuts' walks the emitter tree: render with --light-sampler tree or "
                            "slc (got ") + light_sampler_name(kind) + ")");
  const PackedLights& lights = ctx.lights.packed();
  const uint32_t leaves = lights.header.tree_leaves, directional = lights.header.directional_count;
  // Every cut starts with the root and each directional light.
  const uint32_t capacity = std::max(uint32_t(params_.direct_cut_size), (leaves > 0 ? 1u : 0u) + directional);
  const size_t blocks = cuts_.grid.count();
  const size_t first = cut_nodes_.size(), sizes_first = cut_sizes_.size();
  cut_nodes_.resize(first + blocks * capacity, kNoNode);
  cut_sizes_.resize(sizes_first + blocks, 0);
  timer.time("direct_cuts", [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks), [&](const tbb::blocked_range<size_t>& range) {
      std::vector<uint32_t> cut;
      for (size_t b = range.begin(); b < range.end(); ++b) {
        const GBufferSample& g = cuts_.guides[b];
        cut.clear();
        emitter_tree_cut(lights.tree, leaves, directional, lights.header.tree_distance, g.valid, g.p, g.n, capacity, cut);
        std::copy(cut.begin(), cut.end(), cut_nodes_.begin() + first + b * capacity);
        cut_sizes_[sizes_first + b] = uint32_t(cut.size());
      }
    });
  });
  uint64_t total = 0;
  for (size_t b = 0; b < blocks; ++b) total += cut_sizes_[sizes_first + b];
  counters["rtslc"]["direct_mean_cut_size"] = blocks ? double(total) / double(blocks) : 0.0;
  inputs.params.rtslc_direct_cut_max_size = capacity;
  inputs.params.rtslc_direct_cut_first = uint32_t(first);
  inputs.params.rtslc_direct_sizes_first = uint32_t(sizes_first);
}

vec3 RtslcSampler::estimate_direct(const RenderContext& ctx, const ShadingPoint& point, PixelSampler& sampler,
                                   RayCounters& counters) const {
  PathCounters rays = path_counters();
  vec3 v = estimate_rtslc_direct(ctx.scene, ctx.lights.packed(), ctx.accel, inputs(), point, sampler, rays);
  counters.shadow_rays += rays.shadow_rays;
  return v;
}

void RtslcSampler::build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) {
  const RenderContext& ctx = lighting.context;
  TreeSamplerBase::build(lighting, timer, counters, inputs);
  auto random_pivot = [&](const BlockRect& r) {
    HashRng rng = hash_rng(ctx.options.seed, uint32_t(r.index), 0, 0x52544C43u);  // "RTLC": the pivot stream
    int px = r.x0 + std::min(int(hash_rng_next(rng) * float(r.w)), r.w - 1);
    int py = r.y0 + std::min(int(hash_rng_next(rng) * float(r.h)), r.h - 1);
    return glm::ivec2(px, py);
  };
  auto error = [&](const LightNode& node, const GBufferSample& g) {
    // No pivot surface (a background pixel): split by intensity alone.
    // The distance is bounded below at 0.001 of the pivot's distance from the camera, so that a
    // node touching the pivot does not take every split (it was 0.001 of the scene's diagonal,
    // which a ground plane around a room inflates). Not the singularity clamp: with compensation
    // that is large (0.1 of the distance), and a floor that large made the Cornell box's cuts
    // blind to near VPLs (RMSE against the path tracer 0.24 against 0.09).
    return g.valid ? rtslc_cut_error(node, g.p, g.n, 0.001f * g.depth) : luminance(node.intensity);
  };
  timer.time("cuts", [&] {
    cuts_ = build_block_cuts(ctx, tree_, params_.block_size, uint32_t(params_.cut_size), random_pivot, error);
  });
  counters["rtslc"] = {{"tree_nodes", tree_.node_count()},
                       {"tree_height", tree_.empty() ? 0 : tree_height(tree_)},
                       {"blocks", cuts_.grid.count()},
                       {"mean_cut_size", cuts_.mean_size()}};
  set_cut_inputs(cuts_, inputs);
  if (params_.direct_light == "cuts") {
    cut_nodes_ = cuts_.nodes;
    cut_sizes_ = cuts_.sizes;
    build_direct_cuts(ctx, timer, counters, inputs);
    inputs.cut_nodes = cut_nodes_;
    inputs.cut_sizes = cut_sizes_;
  }
  inputs.params.rtslc_interleave = uint32_t(params_.interleave);
  inputs.params.rtslc_weights = weights_id(weights_);
  inputs.params.rtslc_frame_index = uint32_t(ctx.frame);
}

}  // namespace sst
