#include "core/restir/restir_di.h"

#include "core/accel/embree_accel.h"

namespace sst {

RestirReuse restir_reuse(const RestirDiParams& p) {
  RestirReuse r;
  r.temporal = p.temporal;
  r.temporal_cap = p.temporal_cap;
  r.spatial_passes = p.spatial_passes;
  r.neighbours = p.neighbours;
  r.radius = p.radius;
  r.unbiased = p.combine == "unbiased";
  return r;
}

RestirPush restir_di_push(const RenderContext& ctx, float ray_epsilon) {
  RestirPush push = restir_push(ctx, ray_epsilon, restir_reuse(ctx.options.restir));
  push.light_candidates = uint32_t(ctx.options.restir.candidates);
  push.brdf_candidates = uint32_t(ctx.options.restir.brdf_candidates);
  return push;
}

void add_restir_direct(const RenderContext& ctx, StageTimer& timer, FrameOutput& frame, RestirHistory& history) {
  run_restir(ctx, RestirKind::direct, restir_di_push(ctx, ctx.accel.scene_epsilon()), restir_reuse(ctx.options.restir),
             history, "restir_di", timer, frame);
}

}  // namespace sst
