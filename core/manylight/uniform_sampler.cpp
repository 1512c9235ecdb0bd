#include "core/manylight/uniform_sampler.h"

#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/gpu_sampler_inputs.h"

namespace sst {

IndirectEstimate UniformSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                          PixelSampler& sampler) const {
  IndirectEstimate e;
  size_t n = frame.vpls.size();
  if (n == 0) return e;
  size_t j = std::min(n - 1, size_t(pixel_sampler_get1d(sampler) * float(n)));
  e.value = shade_vpl(frame, point, frame.vpls[j], &e.shadow_rays) * float(n);
  return e;
}

void UniformSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_UNIFORM, out);
}

}  // namespace sst
