#include "core/restir/restir.h"

#include <cstring>
#include <utility>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/camera.h"
#include "core/render/pixel_loop.h"
#include "core/scene/scene_access.h"
#include "core/util/byte_io.h"
#include "core/util/error.h"

namespace sst {
// What the reuse passes read of the other pixels: the round's first hits, the previous stage's
// reservoirs, and the previous frame's last round.
struct RestirFrame {
  const std::vector<RestirSurface>& surfaces;
  const std::vector<RestirReservoir>& reservoirs;
  const RestirHistory& history;
};
}  // namespace sst

#define RESTIR_CTX_PARAM const ::sst::RestirFrame &restir,
#define RESTIR_CTX restir,
#define RESTIR_SURFACE(i) restir.surfaces[i]
#define RESTIR_RESERVOIR(i) restir.reservoirs[i]
#define RESTIR_HISTORY_SURFACE(i) restir.history.surfaces[i]
#define RESTIR_HISTORY_RESERVOIR(i) restir.history.reservoirs[i]
#include "core/restir/restir_stages.h"
#include "core/restir/restir_di_stages.h"
#include "core/restir/restir_gi_stages.h"

namespace sst {

RestirPush restir_push(const RenderContext& ctx, float ray_epsilon, const RestirReuse& reuse) {
  RestirPush push{};
  push.view = view_params(ctx.camera, ctx.width, ctx.height, ctx.options.seed);
  push.view.spp = 1u;
  push.ray_epsilon = ray_epsilon;
  push.flags = (ctx.options.diffuse_only ? RESTIR_DIFFUSE_ONLY : 0u) | (reuse.unbiased ? RESTIR_UNBIASED : 0u);
  push.neighbours = uint32_t(reuse.neighbours);
  push.radius = reuse.radius;
  push.temporal_cap = reuse.temporal_cap;
  return push;
}

RestirPush restir_round_push(const RestirPush& base, uint32_t round, uint32_t pass, bool temporal, bool posed) {
  RestirPush push = base;
  push.view.sample_offset = round;
  push.pass = pass;
  if (temporal) push.flags |= RESTIR_TEMPORAL;
  if (temporal && posed) push.flags |= RESTIR_POSED;
  return push;
}

RestirSampleSpace restir_sample_space(const glsl::LightHeader& lights) {
  return {lights.distribution_size, lights.punctual_count, lights.triangle_count};
}

bool restir_history_usable(bool valid, const glsl::ViewParams& view, const RestirSampleSpace& space,
                           const RestirPush& push, const RestirSampleSpace& now) {
  return valid && view.width == push.view.width && view.height == push.view.height && space == now;
}

namespace {
// The layout sizes are part of the magic: a build whose structs differ cannot misread the bytes.
struct RestirHistoryHeader {
  char magic[8] = {'S', 'S', 'T', 'R', 'H', 'I', '1', '\0'};
  uint32_t surface_bytes = sizeof(RestirSurface);
  uint32_t reservoir_bytes = sizeof(RestirReservoir);
  uint32_t view_bytes = sizeof(glsl::ViewParams);
  RestirSampleSpace space;
  uint64_t pixels = 0;
};
}  // namespace

std::vector<uint8_t> restir_history_bytes(const RestirHistory& history) {
  if (!history.valid) return {};
  RestirHistoryHeader h;
  h.space = history.space;
  h.pixels = history.surfaces.size();
  std::vector<uint8_t> out;
  append_bytes(out, &h);
  append_bytes(out, &history.view);
  append_bytes(out, history.surfaces.data(), h.pixels);
  append_bytes(out, history.reservoirs.data(), h.pixels);
  return out;
}

RestirHistory restir_history_from_bytes(std::span<const uint8_t> bytes) {
  RestirHistory history;
  if (bytes.empty()) return history;
  ByteReader r(bytes, "not a ReSTIR history of this build");
  const RestirHistoryHeader h = r.read<RestirHistoryHeader>();
  const RestirHistoryHeader expected;
  if (std::memcmp(h.magic, expected.magic, sizeof h.magic) != 0 || h.surface_bytes != expected.surface_bytes ||
      h.reservoir_bytes != expected.reservoir_bytes || h.view_bytes != expected.view_bytes)
    throw r.bad("another format");
  r.read(&history.view);
  if (uint64_t(history.view.width) * history.view.height != h.pixels)
    throw r.bad("its view does not match its pixels");
  r.read(history.surfaces, h.pixels);
  r.read(history.reservoirs, h.pixels);
  if (r.left() != 0) throw r.bad("its size does not match its pixels");
  history.space = h.space;
  history.valid = true;
  return history;
}

void add_restir_sums(std::span<const RestirTexel> sums, int spp, RestirKind kind, FrameOutput& frame) {
  const float inv_spp = 1.0f / float(spp);
  const int width = frame.color.width;
  Image& layer = kind == RestirKind::direct ? frame.direct : frame.indirect;
  for (size_t i = 0; i < sums.size(); ++i) {
    const RestirTexel& t = sums[i];
    const int x = int(i % size_t(width)), y = int(i / size_t(width));
    const vec3 d = t.direct * inv_spp;
    layer.set_rgb(x, y, layer.rgb(x, y) + d);
    frame.color.set_rgb(x, y, frame.color.rgb(x, y) + d);
    frame.counters.primary_rays += t.primary_rays;
    frame.counters.shadow_rays += t.shadow_rays;
    frame.counters.bounce_rays += t.bounce_rays;
    frame.counters.nonfinite_samples += t.nonfinite;
  }
}

void run_restir(const RenderContext& ctx, RestirKind kind, const RestirPush& base, const RestirReuse& reuse,
                RestirHistory& history, const char* stage_name, StageTimer& timer, FrameOutput& frame) {
  const size_t pixels = size_t(ctx.width) * size_t(ctx.height);
  const Scene& scene = ctx.scene;
  const PackedLights& lights = ctx.lights.packed();
  const EmbreeAccel& accel = ctx.accel;
  const bool diffuse_only = (base.flags & RESTIR_DIFFUSE_ONLY) != 0u;
  std::vector<RestirSurface> surfaces(pixels);
  std::vector<RestirReservoir> reservoirs(pixels), next(pixels);
  std::vector<RestirTexel> sums(pixels, restir_texel_empty());
  RayCounters unused;  // the rays are counted per pixel, in the sums
  // One pass over every pixel: fn(pixel index, x, y, counters).
  auto pass_over = [&](auto&& fn) {
    for_each_pixel(ctx.width, ctx.height, true, stage_name, unused, [&](int x, int y, RayCounters&) {
      const size_t i = size_t(y) * size_t(ctx.width) + size_t(x);
      PathCounters c = path_counters();
      fn(i, uint(x), uint(y), c);
      restir_texel_count(sums[i], c);
    });
  };
  const RestirSampleSpace space = restir_sample_space(lights.header);
  timer.time(stage_name, [&] {
    for (int round = 0; round < ctx.options.spp; ++round) {
      // A frame's rounds are independent estimates (chained, they were correlated and their mean
      // measured worse); its first round continues the previous frame's last.
      const bool temporal = round == 0 && reuse.temporal && restir_history_kept(history.posed, reuse) &&
                            restir_history_usable(history.valid, history.view, history.space, base, space);
      const RestirPush push = restir_round_push(base, uint32_t(round), 0u, temporal, history.posed);
      pass_over([&](size_t i, uint x, uint y, PathCounters& c) {
        reservoirs[i] = kind == RestirKind::direct
                            ? restir_di_initial_pixel(scene, lights, accel, push, x, y, surfaces[i], c)
                            : restir_gi_initial_pixel(scene, lights, accel, push, x, y, surfaces[i], c);
      });
      if (temporal && history.posed && kind == RestirKind::indirect) {
        const RestirFrame in{surfaces, reservoirs, history};
        pass_over([&](size_t i, uint x, uint y, PathCounters& c) {
          next[i] = restir_gi_validate_pixel(scene, lights, accel, in, push, x, y, c);
        });
        std::swap(history.reservoirs, next);
      }
      if (temporal) {
        const RestirFrame in{surfaces, reservoirs, history};
        pass_over([&](size_t i, uint x, uint y, PathCounters& c) {
          next[i] = restir_temporal_pixel(scene, lights, accel, in, push, x, y, history.view, c);
        });
        std::swap(reservoirs, next);
      }
      for (int pass = 0; pass < reuse.spatial_passes; ++pass) {
        const RestirFrame in{surfaces, reservoirs, history};
        const RestirPush pass_push = restir_round_push(base, uint32_t(round), uint32_t(pass), temporal, false);
        pass_over([&](size_t i, uint x, uint y, PathCounters& c) {
          next[i] = restir_spatial_pixel(scene, lights, accel, in, pass_push, x, y, c);
        });
        std::swap(reservoirs, next);
      }
      pass_over([&](size_t i, uint, uint, PathCounters&) {
        restir_texel_add(sums[i], restir_shade(scene, lights, surfaces[i], diffuse_only, reservoirs[i]));
      });
      // This round is the next one's history (the buffers swap, the next round overwrites).
      std::swap(history.surfaces, surfaces);
      std::swap(history.reservoirs, reservoirs);
      surfaces.resize(pixels);
      reservoirs.resize(pixels);
      history.view = push.view;
      history.space = space;
      history.valid = true;
      history.posed = false;
    }
  });
  add_restir_sums(sums, ctx.options.spp, kind, frame);
}

}  // namespace sst
