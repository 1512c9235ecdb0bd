#include "core/restir/restir_gi.h"

#include <cmath>

#include "core/pt/path_tracer.h"
#include "core/util/error.h"

namespace sst {

RestirGi::RestirGi(const RestirGiParams& p) : params_(p) {
  if (p.max_bounces < 1 || p.max_bounces > 1024)
    throw Error("max_bounces must be in 1..1024 (got " + std::to_string(p.max_bounces) + ")");
  if (p.rr_min_bounces < 0) throw Error("rr_min_bounces must be >= 0");
  if (!(p.reuse_temporal_cap > 0.0f && p.reuse_temporal_cap <= 1000.0f))
    throw Error("reuse_temporal_cap must be in (0, 1000] (got " + std::to_string(p.reuse_temporal_cap) + ")");
  if (p.spatial_passes < 0 || p.spatial_passes > 8)
    throw Error("spatial_passes must be in 0..8 (got " + std::to_string(p.spatial_passes) + ")");
  if (p.neighbours < 1 || p.neighbours > int(RESTIR_MAX_NEIGHBOURS))
    throw Error("neighbours must be in 1..16 (got " + std::to_string(p.neighbours) + ")");
  if (!(p.radius >= 1.0f && p.radius <= 256.0f))
    throw Error("radius must be in 1..256 pixels (got " + std::to_string(p.radius) + ")");
  if (p.combine != "unbiased" && p.combine != "biased")
    throw Error("unknown combine '" + p.combine + "' (valid: unbiased, biased)");
}

nlohmann::json RestirGi::params() const { return params_to_json(params_); }

RestirReuse restir_gi_reuse(const RestirGiParams& p) {
  RestirReuse r;
  r.temporal = p.reuse_temporal;
  r.temporal_cap = p.reuse_temporal_cap;
  r.spatial_passes = p.spatial_passes;
  r.neighbours = p.neighbours;
  r.radius = p.radius;
  r.unbiased = p.combine == "unbiased";
  r.across_poses = p.validate;
  return r;
}

RestirPush restir_gi_push(const RenderContext& ctx, float ray_epsilon, const RestirGiParams& p) {
  RestirPush push = restir_push(ctx, ray_epsilon, restir_gi_reuse(p));
  push.max_bounces = p.max_bounces;
  push.rr_min_bounces = p.rr_min_bounces;
  return push;
}

PathTracerParams restir_gi_direct_params() {
  PathTracerParams p;
  p.max_bounces = 0;
  return p;
}

void RestirGi::restore_history(std::span<const uint8_t> bytes, bool posed) {
  history_ = restir_history_from_bytes(bytes);
  history_.posed = posed;
}

FrameOutput RestirGi::render(const RenderContext& ctx, StageTimer& timer) {
  // The direct light and the AOVs of the frame's samples; its indirect layer is zero.
  FrameOutput frame = PathTracer(restir_gi_direct_params()).render(ctx, timer);
  run_restir(ctx, RestirKind::indirect, restir_gi_push(ctx, ctx.accel.scene_epsilon(), params_),
             restir_gi_reuse(params_), history_, "restir_gi", timer, frame);
  return frame;
}

MethodInfo restir_gi_method_info() {
  MethodInfo info = method_info<RestirGiParams>(
      "restir_gi",
      "ReSTIR GI (Ouyang et al.): per pixel one BRDF-sampled secondary vertex with the light a path from it brings "
      "back, resampled with the previous frame's and the neighbours' (pairwise MIS); direct light as every method's",
      [](const RestirGiParams& p) -> std::unique_ptr<Method> { return std::make_unique<RestirGi>(p); });
  return info;
}

}  // namespace sst
