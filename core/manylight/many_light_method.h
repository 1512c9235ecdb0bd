// The pipeline shared by every VPL method (the list many_light_methods.h):
//   VPL generation -> sampler.prepare (tree, cuts) -> per pixel sample: a jittered camera ray,
//   the direct light exactly as `pt` computes it at its first hit, and one indirect estimate
//   from the sampler at that hit.
// The EXR's `indirect` layer is exactly the sampler's estimate (averaged over spp); the extra
// layers are `indirect_variance` (the variance of that per-pixel mean, for z-tests) and
// `traversal_depth` (tree nodes visited per indirect sample).
#pragma once
#include <memory>

#include "core/manylight/indirect_sampler.h"
#include "core/manylight/many_light_methods.h"
#include "core/pt/path_tracer.h"
#include "core/render/method.h"
#include "core/render/view_length.h"
#include "core/vpl/vpl_generator.h"

namespace sst {

class ManyLightMethod final : public Method {
 public:
  ManyLightMethod(VplParams vpl_params, nlohmann::json params, std::unique_ptr<IndirectSampler> sampler);
  FrameOutput render(const RenderContext& context, StageTimer& timer) override;
  nlohmann::json params() const override { return params_; }
  // For the method's other backends (gpu/many_light_method_vulkan.h), which run the same stages.
  const VplParams& vpl_params() const { return vpl_params_; }
  IndirectSampler& sampler() { return *sampler_; }

 private:
  VplParams vpl_params_;
  nlohmann::json params_;
  std::unique_ptr<IndirectSampler> sampler_;
};

// Where the frame's directional lights aim their light paths (EmissionFocus): discs around the
// camera from VplParams::directional_focus times `view_distance` (median_view_distance, core/
// render/view_length.h) on, so that the VPLs land where the view can see their light. No focus
// when either is 0.
EmissionFocus view_emission_focus(const RenderContext& context, float view_distance, float directional_focus);

// One pixel's sums over its samples: the direct pass's PathSamples (`path`, its `indirect` the
// sampler's estimates) and what the extra layers need. ManyLightMethod::render fills them on the
// CPU, ManyLightTexel holds them on the GPU.
struct ManyLightPixelSums {
  PathSample path;
  vec3 indirect2{0.0f};  // the estimates squared
  uint64_t nodes = 0, indirect_samples = 0;
};

// Pixel (x, y) from its sums of `spp` samples: the layers' means (write_path_means), the variance
// of the indirect mean into `variance` and the nodes per indirect sample into `traversal_depth`.
void write_many_light_pixel(const ManyLightPixelSums& sums, int spp, int x, int y, FrameOutput& frame, Image& variance,
                            Image& traversal_depth);

// The registry entry of each method of the list (many_light_methods.h): MethodInfo
// <name>_method_info(), defined in core/manylight/<name>/<name>_method.cpp.
#define ML_DECLARE_METHOD_INFO(name, id) MethodInfo name##_method_info();
SST_MANY_LIGHT_METHODS(ML_DECLARE_METHOD_INFO)
#undef ML_DECLARE_METHOD_INFO

}  // namespace sst
