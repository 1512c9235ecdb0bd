// ReSTIR DI as every method's direct light (RenderOptions::direct_sampler restir): the estimate of
// the direct light at the first hits, added to a frame the method rendered without it (its paths
// gather no light at vertex 1: path_direct_elsewhere, core/pt/path_stages.h). Its initial pass is
// core/restir/restir_di_stages.h, the rest ReSTIR's (core/restir/restir.h); on Vulkan
// gpu/restir_pass.h. The algorithm and its parameters: docs/restir.md.
#pragma once
#include "core/restir/restir.h"

namespace sst {

// The reuse RenderOptions::restir asks for.
RestirReuse restir_reuse(const RestirDiParams& params);

// The push constants of ReSTIR DI's rounds for ctx.
RestirPush restir_di_push(const RenderContext& ctx, float ray_epsilon);

// Renders ReSTIR DI's direct light for ctx (ctx.options.spp rounds) on the CPU and adds it to
// `frame`'s direct and colour layers and counters; `history` carries temporal reuse across frames.
void add_restir_direct(const RenderContext& ctx, StageTimer& timer, FrameOutput& frame, RestirHistory& history);

}  // namespace sst
