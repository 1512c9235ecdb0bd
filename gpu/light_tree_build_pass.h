// The light tree built on the GPU: the twin of LightTreeBuilder::build for trees "radix"
// and "perfect" (core/lighttree/light_tree.cpp), producing the same LightTree bit for bit (nodes
// memcmp-equal, the same header fields) where the device's float division and sqrt are correctly
// rounded, as on lavapipe. The stages are the CPU's, one compute pass each:
//   VPL bounds, D, thresholds   host (compute_vpl_bounds: also checks every VPL; cheap)
//   sort keys                   light_tree_keys.comp (one invocation per VPL)
//   radix sort                  5 passes of 8 bits over key bits [25, 64), as the CPU: each
//                               light_tree_sort_histogram / _scan / _scatter (stable)
// then, for "radix" (radix_tree_builder.cpp):
//   topology and merge          light_tree_merge.comp (one per leaf, one per workgroup: a lavapipe
//                               bug, see there; the climbs meet through atomic exchanges)
// or, for "perfect" (perfect_tree_builder.cpp; no topology to build, the heap's):
//   leaves                      light_tree_perfect_leaves.comp (one invocation per leaf [L, 2L))
//   merge                       light_tree_perfect_merge.comp, one dispatch per level bottom-up
//                               (one invocation per parent)
// Keys are uvec2 in the shaders: no shaderInt64 needed.
#pragma once
#include <memory>

#include "core/lighttree/light_tree.h"
#include "core/vpl/vpl.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "core/lighttree/light_tree_build_layout.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The passes' pipelines, created once (shader compilation is the slow part on lavapipe); build()
// may be called any number of times. Not thread-safe (the pipelines own one command buffer each).
class GpuLightTreeBuilder {
 public:
  // sst::Error when a shader is not built in.
  explicit GpuLightTreeBuilder(const VulkanContext& context);
  ~GpuLightTreeBuilder();

  // What build_light_tree_gpu does (see there).
  LightTree build(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths = nullptr,
                  LightTreeBuildStats* stats = nullptr, double* gpu_ms = nullptr);
  // The tree's leaves are the VPLs (LightTree::vpls): a temporary set would leave it dangling.
  LightTree build(VplSet&&, const LightTreeParams&, const TreeLengths* = nullptr, LightTreeBuildStats* = nullptr,
                  double* = nullptr) = delete;

 private:
  struct Sorted {
    std::unique_ptr<GpuBuffer> keys, ids;  // by key, as the CPU's sort_vpls leaves its scratch
  };
  Sorted sort(const GpuBuffer& vpls, glsl::LightTreeBuildPush push, LightTreeBuildStats& stats);
  void build_radix(const GpuBuffer& vpls, const Sorted& sorted, glsl::LightTreeBuildPush push, LightTree& tree,
                   LightTreeBuildStats& stats);
  void build_perfect(const GpuBuffer& vpls, const Sorted& sorted, glsl::LightTreeBuildPush push, LightTree& tree,
                     LightTreeBuildStats& stats);

  const VulkanContext& context_;
  std::unique_ptr<ComputePipeline> keys_, histogram_, scan_, scatter_, merge_;
  std::unique_ptr<ComputePipeline> perfect_leaves_, perfect_merge_;
};

// build_light_tree(vpls, params, scene_bounds) on the GPU. Throws sst::Error as the CPU does (bad
// parameters, too many VPLs, a bad VPL), and for tree "agglomerative" (built on the CPU only).
// `stats`: bounds_ms is host wall time; keys_ms, sort_ms and merge_ms are the GPU times of those
// passes (timestamps; a perfect tree's leaves and levels are merge_ms, as on the CPU; hierarchy_ms
// is 0, as on the CPU); total_ms is the wall time of the whole call, uploads and downloads included. `gpu_ms`
// (optional): the GPU time of all passes.
LightTree build_light_tree_gpu(const VulkanContext& context, const VplSet& vpls, const LightTreeParams& params,
                               const TreeLengths* lengths = nullptr, LightTreeBuildStats* stats = nullptr,
                               double* gpu_ms = nullptr);

}  // namespace sst::gpu
