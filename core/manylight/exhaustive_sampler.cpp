#include "core/manylight/exhaustive_sampler.h"

#include "core/manylight/gpu_sampler_inputs.h"
#include "core/vpl/vpl_shading.h"

namespace sst {

vec3 shade_vpl(const ManyLightFrame& frame, const ShadingPoint& point, const Vpl& vpl, uint32_t* shadow_rays) {
  vec3 c = vpl_contribution(vpl, point.p, point.ng, point.basis, point.brdf, point.wo, frame.clamp_distance);
  if (max_component(c) <= 0.0f) return vec3(0.0f);
  ++*shadow_rays;
  if (frame.context.accel.occluded(vpl_shadow_ray(frame.context.accel, point.p, point.ng, vpl))) return vec3(0.0f);
  return c;
}

IndirectEstimate ExhaustiveSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point, PixelSampler&) const {
  IndirectEstimate e;
  for (const Vpl& vpl : frame.vpls) e.value += shade_vpl(frame, point, vpl, &e.shadow_rays);
  return e;
}

void ExhaustiveSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_EXHAUSTIVE, out);
}

}  // namespace sst
