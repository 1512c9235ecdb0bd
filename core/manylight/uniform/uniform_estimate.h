// `uniform`, the estimate at one shading point (shared C++/GLSL source): one VPL drawn uniformly,
// weighted by the VPL count. The simplest unbiased many-light sampler, the baseline of the others.
#ifndef SST_CORE_MANYLIGHT_UNIFORM_UNIFORM_ESTIMATE_H
#define SST_CORE_MANYLIGHT_UNIFORM_UNIFORM_ESTIMATE_H
#include "core/manylight/estimator.h"

SST_BEGIN

SST_FUNC IndirectEstimate estimate_uniform(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  IndirectEstimate e = indirect_estimate_zero();
  uint n = ML_PARAMS.vpl_count;
  if (n == 0u) return e;
  SST_PRECISE float scaled = pixel_sampler_get1d(ps) * float(n);
  uint j = min(n - 1u, uint(scaled));
  vec3 c = shade_vpl(ML_CTX sp, ML_VPL(j), e.shadow_rays);
  SST_PRECISE vec3 v = c * float(n);
  e.value = v;
  return e;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_UNIFORM_UNIFORM_ESTIMATE_H
