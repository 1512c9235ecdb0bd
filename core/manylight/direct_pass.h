// The camera path of every VPL method's direct pass (shared C++/GLSL source): `pt`'s path with
// max_bounces = 0 (direct light at the first hit; -1 for a method that samples the direct light
// itself), which with clamp compensation also carries the light the VPLs' singularity clamp
// removes (VplParams::clamp_compensation; core/pt/path_stages.h's PathConfig says how). The
// compensating path goes on for as many bounces as a light path deposits VPLs, with Russian
// roulette after as many, so that it adds back exactly the light paths the VPL set stands for.
#ifndef SST_CORE_MANYLIGHT_DIRECT_PASS_H
#define SST_CORE_MANYLIGHT_DIRECT_PASS_H
#include "core/pt/path_stages.h"

SST_BEGIN

// direct_elsewhere: the first hit's direct light is estimated by the method itself (rtslc's cuts) or
// by ReSTIR DI, not by the path. compensation_max_bounces 0: no compensation; else
// VplParams::vpl_max_bounces, with compensation_rr_min_bounces = vpl_min_bounces. clamp_distance
// and clamp_per_depth: VplStats'.
SST_FUNC PathConfig many_light_direct_config(bool direct_elsewhere, bool diffuse_only, int compensation_max_bounces,
                                             int compensation_rr_min_bounces, float clamp_distance,
                                             float clamp_per_depth) {
  PathConfig c = path_config(direct_elsewhere ? -1 : 0, 0, diffuse_only);
  if (compensation_max_bounces > 0 && (clamp_distance > 0.0f || clamp_per_depth > 0.0f)) {
    c.max_bounces = compensation_max_bounces;
    c.rr_min_bounces = compensation_rr_min_bounces;
    c.first_vertex_light = !direct_elsewhere;
    c.clamp_distance = clamp_distance;
    c.clamp_per_depth = clamp_per_depth;
  }
  return c;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_DIRECT_PASS_H
