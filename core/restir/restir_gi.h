// `restir_gi`: ReSTIR GI (Ouyang et al. 2021) as a method. Per pixel and sample, the direct light
// at the first hit as every method takes it (`pt`'s path with max_bounces 0, or ReSTIR DI under
// --direct-sampler restir), and the indirect light from a reservoir of secondary vertices: one
// BRDF-sampled vertex per pixel with the radiance a path from it brings back
// (core/restir/restir_gi_stages.h), merged with the previous frame's and its neighbours' by the
// reuse ReSTIR DI uses (core/restir/restir_stages.h). On Vulkan: gpu/restir_gi_vulkan.h.
#pragma once
#include <memory>
#include <string>

#include "core/render/method.h"
#include "core/restir/restir.h"
#include "core/util/params.h"

namespace sst {

struct RestirGiParams {
  int max_bounces = 8;
  int rr_min_bounces = 3;
  bool reuse_temporal = true;
  float reuse_temporal_cap = 5.0f;
  int spatial_passes = 1;
  int neighbours = 5;
  float radius = 30.0f;
  std::string combine = "unbiased";
  bool validate = true;

  template <class V>
  void visit(V&& v) {
    v("max_bounces", max_bounces,
      "indirect bounces of the light a secondary vertex gathers, counted from the pixel as pt counts them (1: the "
      "vertex's direct light only)");
    v("rr_min_bounces", rr_min_bounces, "indirect bounces, counted from the pixel, before Russian roulette may end a path");
    v("reuse_temporal", reuse_temporal,
      "temporal reuse in sequences: each frame's first sample merges the previous frame's reservoir where the "
      "pixel's point was seen");
    v("reuse_temporal_cap", reuse_temporal_cap,
      "the history's M is capped at this many times the new reservoir's (one candidate a pixel: the history is at "
      "most this many frames of samples)");
    v("spatial_passes", spatial_passes, "spatial reuse passes (0: none)");
    v("neighbours", neighbours, "neighbours each spatial pass merges (1..16)");
    v("radius", radius, "radius in pixels within which neighbours are drawn");
    v("combine", combine,
      "how merged reservoirs are weighted (pairwise MIS): unbiased (a neighbour's weight for the pixel's own sample "
      "checked with a shadow ray) or biased (without)");
    v("validate", validate,
      "after the scene moves (animation, moving lights), find the history's vertices again on their triangles and "
      "trace their radiance anew before temporal reuse (the paper's validation, every vertex of such a frame); false: "
      "drop the history on such frames (spatial reuse only)");
  }
};

class RestirGi final : public Method {
 public:
  explicit RestirGi(const RestirGiParams& params);
  FrameOutput render(const RenderContext& context, StageTimer& timer) override;
  nlohmann::json params() const override;
  // The history's vertices and radiance belong to the old pose: the next frame validates them.
  void scene_posed() override { history_.posed = true; }
  std::vector<uint8_t> save_history() const override { return restir_history_bytes(history_); }
  void restore_history(std::span<const uint8_t> bytes, bool posed) override;
  const RestirGiParams& gi_params() const { return params_; }

 private:
  RestirGiParams params_;
  RestirHistory history_;
};

// The reuse and the push constants of ReSTIR GI's rounds for ctx.
RestirReuse restir_gi_reuse(const RestirGiParams& params);
RestirPush restir_gi_push(const RenderContext& ctx, float ray_epsilon, const RestirGiParams& params);

// The path of the frame's direct light and first-hit AOVs: `pt` with max_bounces 0.
struct PathTracerParams;
PathTracerParams restir_gi_direct_params();

MethodInfo restir_gi_method_info();

}  // namespace sst
