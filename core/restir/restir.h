// ReSTIR's schedule of passes over a frame, for ReSTIR DI (every method's direct light,
// core/restir/restir_di.h) and ReSTIR GI (the method `restir_gi`, core/restir/restir_gi.h): `spp`
// independent rounds, each its initial pass, a temporal pass (the frame's first round, with
// history), the spatial passes and the shading pass (core/restir/restir_stages.h). This is the
// CPU's schedule; gpu/restir_pass.h is the GPU's, the same passes in the same order, and both add
// their sums to the frame through add_restir_sums, so the backends give the same bits (with
// --accel flat). The algorithm and its parameters: docs/restir.md.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/lights/light_layout.h"
#include "core/render/method.h"
#include "core/restir/restir_layout.h"
#include "core/util/stage_timer.h"

namespace sst {

// Which light a schedule estimates: its initial pass, and the layer its sums go to.
enum class RestirKind { direct, indirect };

// The reuse every ReSTIR shares (RestirDiParams', RestirGiParams').
struct RestirReuse {
  bool temporal = true;
  float temporal_cap = 1.0f;
  int spatial_passes = 1;
  int neighbours = 5;
  float radius = 30.0f;
  bool unbiased = true;
  // Whether the history outlives a pose change of the scene (evaluated in the new pose, ReSTIR GI's
  // vertices validated), or is dropped.
  bool across_poses = true;
};

// Whether a history, posed anew since or not, takes part in temporal reuse under `reuse`.
inline bool restir_history_kept(bool posed, const RestirReuse& reuse) { return !posed || reuse.across_poses; }

// What a history's samples are named by: lights by their distribution entry, GI vertices by their
// triangle. A history serves another pose of the scene only where these mean the same.
struct RestirSampleSpace {
  uint32_t lights = 0, punctual = 0, triangles = 0;
  bool operator==(const RestirSampleSpace&) const = default;
};
RestirSampleSpace restir_sample_space(const glsl::LightHeader& lights);

// What temporal reuse keeps between frames: the last round's first hits, its final reservoirs and
// the view it saw them with. `posed`: the scene was posed anew since (FrameRenderer::prepare,
// Method::scene_posed), so the next temporal pass evaluates the history in the scene as it is now
// (RESTIR_POSED).
struct RestirHistory {
  std::vector<RestirSurface> surfaces;
  std::vector<RestirReservoir> reservoirs;
  glsl::ViewParams view{};
  RestirSampleSpace space;
  bool valid = false;
  bool posed = false;
};

// A history as bytes for sequence checkpoints (Method::save_history; empty: no history) and back;
// restir_history_from_bytes throws sst::Error when the bytes are not a history of this build.
std::vector<uint8_t> restir_history_bytes(const RestirHistory& history);
RestirHistory restir_history_from_bytes(std::span<const uint8_t> bytes);

// The push constants every round of ctx starts from: the view, the ray offset, the reuse; the
// caller adds its initial pass's fields.
RestirPush restir_push(const RenderContext& ctx, float ray_epsilon, const RestirReuse& reuse);

// `base` for round `round` and spatial pass `pass`, with or without a temporal pass, whose history
// is `posed` (RestirHistory::posed) or not.
RestirPush restir_round_push(const RestirPush& base, uint32_t round, uint32_t pass, bool temporal, bool posed);

// Whether history of `view` over `space` (valid) can serve a round of `push` over `now`: the same
// image size and sample space.
bool restir_history_usable(bool valid, const glsl::ViewParams& view, const RestirSampleSpace& space,
                           const RestirPush& push, const RestirSampleSpace& now);

// Runs ctx.options.spp rounds on the CPU from `base` (restir_push and the initial pass's fields)
// and adds them to `frame` (add_restir_sums). `history` carries the last round to the next
// frame's first; timed as stage `stage`.
void run_restir(const RenderContext& ctx, RestirKind kind, const RestirPush& base, const RestirReuse& reuse,
                RestirHistory& history, const char* stage, StageTimer& timer, FrameOutput& frame);

// The per-pixel sums of `spp` rounds (row-major, the frame's size) added to `frame`: the direct
// (kind direct) or indirect layer and the colour gain sum / spp, the counters the rays, and a
// non-finite round is counted.
void add_restir_sums(std::span<const RestirTexel> sums, int spp, RestirKind kind, FrameOutput& frame);

}  // namespace sst
