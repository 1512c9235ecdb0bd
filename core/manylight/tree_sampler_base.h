// What every light-tree sampler (slc, sst, rtslc, hybrid) shares: its tree parameters and the
// per-frame build of the tree, timed as stage "tree_build", with the tree's statistics recorded
// as counters["tree"] so that every tree method's record can be compared.
#pragma once
#include "core/lighttree/light_tree.h"
#include "core/manylight/indirect_sampler.h"

namespace sst {

class TreeSamplerBase : public IndirectSampler {
 public:
  explicit TreeSamplerBase(LightTreeParams tree_params);
  void set_tree_builder(LightTreeBuildFn builder) override { builder_ = std::move(builder); }
  const LightTree& tree() const { return tree_; }

 protected:
  // Builds the tree and sets its part of `inputs`; samplers with more to build call it first.
  void build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) override;

  LightTreeParams tree_params_;
  LightTree tree_;

 private:
  LightTreeBuildFn builder_;      // empty: cpu_builder_
  LightTreeBuilder cpu_builder_;  // kept, with tree_'s storage, so that a sequence's rebuilds allocate nothing
};

}  // namespace sst
