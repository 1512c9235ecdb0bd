// ReSTIR DI as every method's direct light (RenderOptions::direct_sampler restir): the estimate of
// the direct light at the first hits, added to a frame the method rendered without it (its paths
// gather no light at vertex 1: path_direct_elsewhere, core/pt/path_stages.h). The stages are
// core/restir/restir_di_stages.h; this is their CPU schedule, gpu/restir_di_pass.h the GPU's, and
// both add their sums to the frame through add_restir_sums, so the backends give the same bits
// (with --accel flat). The algorithm and its parameters: docs/restir.md.
#pragma once
#include <span>
#include <vector>

#include "core/render/method.h"
#include "core/restir/restir_di_layout.h"
#include "core/util/stage_timer.h"

namespace sst {

// What temporal reuse keeps between rounds and frames: the last round's first hits, its final
// reservoirs and the view it saw them with.
struct RestirDiHistory {
  std::vector<RestirSurface> surfaces;
  std::vector<RestirReservoir> reservoirs;
  glsl::ViewParams view{};
  bool valid = false;
};

// Renders ReSTIR DI's direct light for ctx (ctx.options.spp rounds, one per pixel sample index)
// on the CPU and adds it to `frame`'s direct and colour layers and counters. `history` carries the
// last round to the next frame's first (RestirDiParams::temporal); reset where sizes differ.
void add_restir_direct(const RenderContext& ctx, StageTimer& timer, FrameOutput& frame, RestirDiHistory& history);

// The per-pixel sums of `spp` rounds (row-major, ctx's size) added to `frame`: direct light and
// colour gain sum / spp, the counters the rays, a non-finite round is counted.
void add_restir_sums(std::span<const RestirTexel> sums, int spp, FrameOutput& frame);

// The push constants of a round for these options (view.sample_offset: the round; `pass`: the
// spatial pass; `temporal`: a temporal pass runs, over history), shared by both schedules.
RestirDiPush restir_push(const RenderContext& ctx, float ray_epsilon, uint32_t round, uint32_t pass, bool temporal);

// Whether history of `view` (valid) can serve a round of `push`: the same image size.
bool restir_history_usable(bool valid, const glsl::ViewParams& view, const RestirDiPush& push);

}  // namespace sst
