// Weighted reservoir sampling as resampled importance sampling (RIS) and ReSTIR use it (shared
// C++/GLSL source; Talbot et al. 2005, Bitterli et al. 2020 Alg. 1-4): a stream of candidates,
// each with a resampling weight w, keeps one with probability w / (sum of the weights), in one
// pass and constant memory. The kept sample's contribution weight W = (sum of the weights) /
// (Z p^(y)) then stands in for 1 / (its density) in the estimate f(y) W: Z = 1 when each w
// already holds its candidate's share (RIS with MIS weights), else the number of candidates that
// could have produced y (merging reservoirs, where each candidate is a reservoir of M samples).
// Every reservoir in sst is built from these two functions: ReSTIR DI's light samples
// (core/restir/restir_di_stages.h), ReSTIR GI's vertices and GI-1.0's world-space reservoirs
// (core/gi10/gi10_cache.h).
#ifndef SST_CORE_RESTIR_RESERVOIR_H
#define SST_CORE_RESTIR_RESERVOIR_H
#include "core/math/vector_math.h"

SST_BEGIN

// Streams a candidate of weight w into a reservoir whose weights sum to weight_sum, with u
// uniform in [0, 1): true when the candidate replaces the kept sample. A weight that is not
// positive (zero, negative, NaN) never enters.
SST_FUNC bool reservoir_accept(SST_INOUT(float) weight_sum, float w, float u) {
  if (!(w > 0.0f) || !is_finite(w)) return false;
  SST_PRECISE float sum = weight_sum + w;
  weight_sum = sum;
  SST_PRECISE float threshold = u * sum;
  return threshold < w;
}

// The kept sample's contribution weight W = weight_sum / (z target), target being p^(y) where
// the reservoir is used; 0 where that is not positive (the sample contributes nothing there).
SST_FUNC float reservoir_contribution_weight(float weight_sum, float z, float target) {
  if (!(target > 0.0f) || !(z > 0.0f)) return 0.0f;
  SST_PRECISE float w = weight_sum / (z * target);
  return is_finite(w) ? w : 0.0f;
}

SST_END

#endif  // SST_CORE_RESTIR_RESERVOIR_H
