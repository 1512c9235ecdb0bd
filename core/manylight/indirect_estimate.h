// One indirect estimate at a shading point by the sampler ML_PARAMS.method names (shared C++/GLSL
// source): the per-pixel work of every VPL method on both backends. The pixel sampler continues
// the pixel sample's stream where the camera ray and the direct light left it.
#ifndef SST_CORE_MANYLIGHT_INDIRECT_ESTIMATE_H
#define SST_CORE_MANYLIGHT_INDIRECT_ESTIMATE_H
#include "core/manylight/exhaustive_estimate.h"
#include "core/manylight/hybrid_estimate.h"
#include "core/manylight/rtslc_estimate.h"
#include "core/manylight/slc_estimate.h"
#include "core/manylight/sst_estimate.h"
#include "core/manylight/uniform_estimate.h"

SST_BEGIN

SST_FUNC IndirectEstimate estimate_indirect(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  switch (ML_PARAMS.method) {
    case ML_METHOD_EXHAUSTIVE: return estimate_exhaustive(ML_CTX sp);
    case ML_METHOD_UNIFORM: return estimate_uniform(ML_CTX sp, ps);
    case ML_METHOD_SLC: return estimate_slc(ML_CTX sp, ps);
    case ML_METHOD_SST: return estimate_sst(ML_CTX sp, ps);
    case ML_METHOD_RTSLC: return estimate_rtslc(ML_CTX sp, ps);
    case ML_METHOD_HYBRID: return estimate_hybrid(ML_CTX sp, ps);
  }
  return indirect_estimate_zero();
}

SST_END

#endif  // SST_CORE_MANYLIGHT_INDIRECT_ESTIMATE_H
