// `rtslc` with direct_light = cuts: RTSLC's per-block light cuts on the scene's own emitters
// (Lin & Yuksel 2020's real-light case, the Cornell box lit by 12,146 emissive triangles), in
// the common subset of C++ and GLSL. The emitter tree is the one the tree and slc light samplers
// walk (core/lights/emitter_tree.h); rtslc_sampler.cpp builds each block's cut of it at the
// block's pivot pixel. Every pixel of the block walks once from each of its cut nodes (every
// r^2-th with interleaving) to a light, by the light sampler's child weights, takes one point on
// that light and one shadow ray, and sums the estimates, each times r^2 / its walk's
// probability. The cut's subtrees are disjoint and cover every light, so the sum is unbiased;
// there is no BRDF sampling of emitters to weigh it against (trace_path runs with
// max_bounces = -1: the first hit's own emission only).
//
// Hooks: the scene's, the lights' (core/lights/light_sample.h), the rays' (core/pt/trace_path.h)
// and the estimators' (core/manylight/estimator.h), all bound by the includer.
#ifndef SST_CORE_MANYLIGHT_RTSLC_RTSLC_DIRECT_H
#define SST_CORE_MANYLIGHT_RTSLC_RTSLC_DIRECT_H
#include "core/lights/emitter_tree.h"
#include "core/manylight/estimator.h"
#include "core/manylight/rtslc/rtslc_estimate.h"
#include "core/pt/trace_path.h"

SST_BEGIN

// The direct light at sp from the cut of sp's block: one light sample per cut node of sp's slot.
SST_FUNC vec3 estimate_rtslc_direct(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM ML_CTX_PARAM SST_IN(ShadingPoint) sp,
                                    SST_INOUT(PixelSampler) ps, SST_INOUT(PathCounters) counters) {
  vec3 sum = vec3(0.0f);
  uint max_size = ML_PARAMS.rtslc_direct_cut_max_size;
  if (max_size == 0u) return sum;
  RtslcPixelShare share = rtslc_pixel_share(ML_CTX sp);
  uint slots = share.slots;
  uint first = ML_PARAMS.rtslc_direct_cut_first + share.block * max_size;
  uint size = ML_CUT_SIZE(ML_PARAMS.rtslc_direct_sizes_first + share.block);
  for (uint i = share.slot; i < size; i += slots) {
    vec2 u = pixel_sampler_get2d(ps);
    float prob = 1.0f;
    uint entry = emitter_tree_descend(LIGHT_CTX ML_CUT_NODE(first + i), sp.p, sp.basis.n, u.x, prob);
    if (entry == LIGHT_NONE || !(prob > 0.0f)) continue;
    LightSample ls;
    vec2 b;
    if (!light_sample_entry(SCENE_CTX LIGHT_CTX sp.p, entry, prob, u, ls, b)) continue;
    vec3 c = shade_light_sample(RAY_CTX sp.p, sp.ng, sp.lift, sp.offset, sp.brdf, sp.basis, sp.wo, ls, false, counters);
    SST_PRECISE vec3 v = c * float(slots);
    sum += v;
  }
  return sum;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_RTSLC_RTSLC_DIRECT_H
