// `exhaustive`, the estimate at one shading point (shared C++/GLSL source): every VPL with its
// shadow ray, summed in VPL order. Deterministic given the shading point; the VPL ground truth
// the unbiased samplers converge to (docs/design/methods.md).
#ifndef SST_CORE_MANYLIGHT_EXHAUSTIVE_EXHAUSTIVE_ESTIMATE_H
#define SST_CORE_MANYLIGHT_EXHAUSTIVE_EXHAUSTIVE_ESTIMATE_H
#include "core/manylight/estimator.h"

SST_BEGIN

// VPLs [first, end) of the set added to `sum`, the sum of the VPLs before `first`: one call covers
// all of them, or, where a device bounds a shader's loop iterations (lavapipe), one slice per
// dispatch continues the previous slice's sum, so that the result has the bits of one call.
SST_FUNC IndirectEstimate estimate_exhaustive_range(ML_CTX_PARAM SST_IN(ShadingPoint) sp, uint first, uint end,
                                                    vec3 sum) {
  IndirectEstimate e = indirect_estimate_zero();
  e.value = sum;
  for (uint j = first; j < end && j < ML_PARAMS.vpl_count; ++j) {
    ML_COUNT_ITERATION();
    vec3 c = shade_vpl(ML_CTX sp, ML_VPL(j), e.shadow_rays);
    e.value += c;
  }
  return e;
}

// `ps` is unused (the sum draws nothing); every estimate_<name> takes it, so that the estimate
// switch calls them alike.
SST_FUNC IndirectEstimate estimate_exhaustive(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  return estimate_exhaustive_range(ML_CTX sp, 0u, ML_PARAMS.vpl_count, vec3(0.0f));
}

SST_END

#endif  // SST_CORE_MANYLIGHT_EXHAUSTIVE_EXHAUSTIVE_ESTIMATE_H
