// The interface every many-light method implements: given the frame's VPLs, build what the
// method needs (a light tree, per-block cuts) and estimate the indirect light at one shading
// point with the method's shared kernel (<name>/<name>_estimate.h). ManyLightMethod
// (many_light_method.h) does everything around it: VPL generation, camera rays, direct light,
// accumulation, AOVs, counters, timings.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/manylight/estimator.h"
#include "core/manylight/sampler_inputs.h"
#include "core/render/method.h"
#include "core/util/error.h"
#include "core/vpl/vpl.h"

namespace sst {

struct LightTree;
struct LightTreeParams;
struct LightTreeBuildStats;

// Builds a frame's light tree as build_light_tree does, possibly elsewhere (the Vulkan backend's
// GPU builder); sets *built_on to where it ran ("cpu" or "gpu").
using LightTreeBuildFn = std::function<LightTree(const VplSet& vpls, const LightTreeParams& params,
                                                 const TreeLengths* lengths, LightTreeBuildStats* stats,
                                                 std::string* built_on)>;

// What a frame is lit by, for a sampler to prepare from: the VPLs, their clamp, and the render
// context (scene, camera, options) they light.
struct VplLighting {
  const RenderContext& context;
  const VplSet& vpls;
  // The singularity clamp c = vpl_clamp_at(clamp_distance, clamp_per_depth, depth) (VplStats).
  float clamp_distance;
  float clamp_per_depth;
  float view_distance;  // median_view_distance of the frame's camera (TreeLengths)
};

class IndirectSampler {
 public:
  virtual ~IndirectSampler() = default;
  // Per-frame preparation: the method's tree and cuts, then inputs(); `counters` receives
  // method-specific counters.
  void prepare(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters);
  // One indirect sample at `point`: the method's estimate_<name>(inputs(), point, sampler), the
  // function the Vulkan backend's estimate switch calls for SamplerParams.method too
  // (gpu/shaders/indirect_sampler.glsl); thread-safe. Call after prepare().
  virtual IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const = 0;
  // Whether the sampler estimates the direct light itself (rtslc with direct_light = cuts): then
  // the method's camera path takes only the first hit's emission and estimate_direct the rest,
  // drawing from the pixel sampler before estimate(), as the Vulkan backend does. Otherwise every
  // method's direct light is trace_path's with max_bounces = 0. Valid after prepare().
  bool estimates_direct() const { return inputs_.params.rtslc_direct_cut_max_size > 0; }
  virtual vec3 estimate_direct(const RenderContext& ctx, const ShadingPoint& point, PixelSampler& sampler,
                               RayCounters& counters) const {
    return vec3(0.0f);
  }
  // What estimate() reads: the method id and parameters, views of the VPLs, tree, cuts and mock
  // cut (the Vulkan backend uploads them). Valid until the next prepare().
  const SamplerInputs& inputs() const { return inputs_; }
  // Replaces how prepare() builds the frame's tree (samplers without a tree ignore it); an empty
  // function restores the CPU builder.
  virtual void set_tree_builder(LightTreeBuildFn builder) {}

 protected:
  // ML_METHOD_<name> (many_light_layout.h, from the list many_light_methods.h).
  virtual uint32_t method_id() const = 0;
  // The method's own preparation (tree, cuts) and its part of `inputs`, which holds the
  // frame-wide part already.
  virtual void build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) {}

 private:
  SamplerInputs inputs_;
};

}  // namespace sst
