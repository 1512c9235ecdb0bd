// How every method samples the direct light at its camera rays' first hits: `nee` (each path's
// own next-event estimation with MIS, core/pt/path_stages.h) or `restir` (ReSTIR DI, Bitterli et
// al. 2020: reservoirs of light samples resampled across pixels; core/restir/). The options live
// here, with RenderOptions, because every method honours them; the algorithm lives in core/restir.
#pragma once
#include <string>

namespace sst {

// ReSTIR DI's parameters (RenderOptions::restir). Defaults: the paper's (32 light candidates, 5
// neighbours within 30 pixels), with one BRDF candidate so that glossy reflections of emitters
// are found as path tracing's MIS finds them, and the history's M capped at 1x the new
// reservoir's, not the paper's 20x (measured: docs/restir.md).
struct RestirDiParams {
  int candidates = 32;
  int brdf_candidates = 1;
  bool temporal = true;
  float temporal_cap = 1.0f;
  int spatial_passes = 1;
  int neighbours = 5;
  float radius = 30.0f;
  std::string combine = "unbiased";

  template <class V>
  void visit(V&& v) {
    v("restir_candidates", candidates,
      "ReSTIR DI: light samples per pixel drawn from --light-sampler, resampled (RIS) by their unshadowed "
      "contribution");
    v("restir_brdf_candidates", brdf_candidates,
      "ReSTIR DI: BRDF-sampled rays per pixel whose emitter hit joins the candidates (0 or 1; combined with the "
      "light samples by the balance heuristic, so glossy reflections of area lights keep their light)");
    v("restir_temporal", temporal,
      "ReSTIR DI: temporal reuse in sequences: each frame's first sample merges each pixel's reservoir with the "
      "one the previous frame left where its point was, found through the motion of the camera (a frame's "
      "samples stay independent of each other)");
    v("restir_temporal_cap", temporal_cap,
      "ReSTIR DI: the history's M is capped at this many times the new reservoir's, so that old samples cannot "
      "dominate for ever (the paper uses 20; with spatial reuse feeding the history, 1 had the lowest error "
      "here: docs/restir.md)");
    v("restir_spatial_passes", spatial_passes, "ReSTIR DI: spatial reuse passes (0: none)");
    v("restir_neighbours", neighbours, "ReSTIR DI: neighbours each spatial pass merges (1..16)");
    v("restir_radius", radius, "ReSTIR DI: radius in pixels within which neighbours are drawn");
    v("restir_combine", combine,
      "ReSTIR DI: how a spatial pass weights the merged reservoirs (pairwise MIS): unbiased (a neighbour's "
      "weight for the pixel's own sample checked with a shadow ray) or biased (without: one ray cheaper per "
      "neighbour, darkens shadow edges)");
  }
};

// The valid values of RenderOptions::direct_sampler: "nee, restir".
const char* direct_sampler_names();

// sst::Error naming the bad value.
void validate(const RestirDiParams& params);

}  // namespace sst
