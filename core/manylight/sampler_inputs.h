// What the indirect estimators (<name>/<name>_estimate.h) read, on the CPU: the sampler's
// parameters, the VPLs, the light tree and the per-block cuts that IndirectSampler::prepare built,
// and the scene the shadow rays are traced in. The Vulkan backend uploads the same (many_light_layout.h).
// Also the hooks through which the shared kernels reach it (estimator.h lists them).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lighttree/light_tree.h"
#include "core/manylight/many_light_layout.h"
#include "core/vpl/vpl.h"

namespace sst {

// Views into the sampler's state; valid until its next prepare(). Empty spans for what a method
// does not use.
struct SamplerInputs {
  SamplerParams params{};
  std::span<const Vpl> vpls;
  const LightTree* tree = nullptr;  // tree samplers' light tree
  std::span<const uint32_t> cut_nodes;
  std::span<const uint32_t> cut_sizes;
  std::vector<CutGuide> guides;
  std::span<const uint32_t> mock_cut;
  const EmbreeAccel* accel = nullptr;  // where shadow rays are traced
};

// Starts `out` afresh for `method` (ML_METHOD_<name>) with the frame-wide inputs.
inline void begin_sampler_inputs(uint32_t method, std::span<const Vpl> vpls, float clamp_distance,
                                 float clamp_per_depth, const EmbreeAccel& accel, SamplerInputs& out) {
  out = {};
  out.params.method = method;
  out.params.vpl_count = uint32_t(vpls.size());
  out.params.clamp_distance = clamp_distance;
  out.params.clamp_per_depth = clamp_per_depth;
  out.params.tree_root = kNoNode;
  out.vpls = vpls;
  out.accel = &accel;
}

// The tree and where its root and leaves are.
inline void set_tree_inputs(const LightTree& tree, SamplerInputs& out) {
  out.tree = &tree;
  out.params.tree_root = tree.empty() ? kNoNode : tree.root;
  out.params.tree_first_leaf = tree.first_leaf;
  out.params.tree_node_count = tree.node_count();
}

// The shadow ray between x (geometric normal ng, on the VPL's side) and a VPL at p with normal n,
// both ends lifted off their surfaces (EmbreeAccel::shadow_ray).
inline bool sampler_inputs_occluded(const SamplerInputs& ml, vec3 x, vec3 ng, vec3 p, vec3 n) {
  return ml.accel->occluded(ml.accel->shadow_ray(x, ng, p, n));
}

}  // namespace sst

#define ML_CTX_PARAM const ::sst::SamplerInputs &ml,
#define ML_CTX ml,
#define ML_PARAMS ml.params
#define ML_NODE(i) ml.tree->node(i)
#define ML_VPL(j) ml.vpls[j]
#define ML_CUT_NODE(i) ml.cut_nodes[i]
#define ML_CUT_SIZE(b) ml.cut_sizes[b]
#define ML_CUT_GUIDE(b) ml.guides[b]
#define ML_MOCK_CUT(j) ml.mock_cut[j]
#define ML_OCCLUDED(x, ng, p, n) ::sst::sampler_inputs_occluded(ml, x, ng, p, n)
#define ML_COUNT_ITERATION()
