#include "core/brsm/brsm_generator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>

#include "core/shading/surface.h"

namespace sst {

// The CPU's buffers behind the BRSM_* hooks (each element written by one step only).
struct BrsmBuffers {
  BrsmGSample* gbuffer;
  BrsmTexel* texels;
  vec2* mip;
  Vpl* vpls;
};

}  // namespace sst

#define BRSM_CTX_PARAM const ::sst::BrsmBuffers &brsm,
#define BRSM_CTX brsm,
#define BRSM_GSAMPLE(i) brsm.gbuffer[i]
#define BRSM_TEXEL(i) brsm.texels[i]
#define BRSM_MIP(i) brsm.mip[i]
#define BRSM_STORE_GSAMPLE(i, g) brsm.gbuffer[i] = g
#define BRSM_STORE_TEXEL(i, t) brsm.texels[i] = t
#define BRSM_STORE_MIP(i, m) brsm.mip[i] = m
#define BRSM_STORE_VPL(i, v) brsm.vpls[i] = v
#include "core/brsm/brsm.h"

namespace sst {
namespace {

template <class F>
void parallel_each(uint32_t count, F&& f) {
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, 256), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

}  // namespace

std::vector<BrsmMap> brsm_maps(const PackedLights& lights, int vpls, int max_maps) {
  const std::vector<glsl::LightCdfEntry>& dist = lights.distribution;
  const uint32_t n = uint32_t(dist.size());
  uint32_t emitting = 0;
  double total = 0.0;
  for (const auto& e : dist)
    if (e.pmf > 0.0f) {
      ++emitting;
      total += double(e.pmf);
    }
  if (emitting == 0 || vpls < 1) return {};
  const uint32_t limit = uint32_t(std::min(max_maps, vpls));
  std::vector<std::pair<uint32_t, uint32_t>> ranges;
  if (emitting <= limit) {
    for (uint32_t i = 0; i < n; ++i)
      if (dist[i].pmf > 0.0f) ranges.emplace_back(i, i + 1);
  } else {
    // Runs of consecutive entries, each closed where the running power passes the next of
    // `limit` equal shares.
    double acc = 0.0;
    uint32_t first = 0;
    for (uint32_t i = 0; i < n; ++i) {
      acc += double(dist[i].pmf);
      bool last = i + 1 == n;
      if (last || (ranges.size() + 1 < limit && acc >= total * double(ranges.size() + 1) / double(limit))) {
        ranges.emplace_back(first, i + 1);
        first = i + 1;
      }
    }
  }
  std::vector<BrsmMap> maps;
  std::vector<double> shares;
  for (auto [first, end] : ranges) {
    double share = 0.0;
    for (uint32_t i = first; i < end; ++i) share += double(dist[i].pmf);
    if (!(share > 0.0)) continue;
    BrsmMap m{};
    m.first_light = first;
    m.end_light = end;
    m.cdf_start = first > 0 ? dist[first - 1].cdf_hi + dist[first - 1].cdf_lo : 0.0f;
    m.pmf_sum = float(share);
    maps.push_back(m);
    shares.push_back(share / total);
  }
  // One VPL each, the rest in proportion to power by largest remainders.
  const uint32_t rest = uint32_t(vpls) - uint32_t(maps.size());
  std::vector<double> remainder(maps.size());
  uint32_t given = 0;
  for (size_t k = 0; k < maps.size(); ++k) {
    double ideal = double(rest) * shares[k];
    uint32_t whole = uint32_t(std::floor(ideal));
    maps[k].vpl_count = 1 + whole;
    remainder[k] = ideal - double(whole);
    given += whole;
  }
  std::vector<size_t> order(maps.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return remainder[a] > remainder[b]; });
  for (size_t k = 0; given < rest; ++k, ++given) ++maps[order[k % order.size()]].vpl_count;
  uint32_t offset = 0;
  for (BrsmMap& m : maps) {
    m.vpl_offset = offset;
    offset += m.vpl_count;
  }
  return maps;
}

uint32_t brsm_auto_resolution(const std::vector<BrsmMap>& maps, float texels_per_vpl) {
  uint32_t most = 0;
  for (const BrsmMap& m : maps) most = std::max(most, m.vpl_count);
  const double texels = double(texels_per_vpl) * double(most);
  uint32_t side = 16;
  while (side < 4096 && double(side) * double(side) < texels) side *= 2;
  return side;
}

BrsmPlan brsm_plan(const Scene& scene, const PackedLights& lights, const VplParams& params, const ViewParams& view,
                   uint32_t seed, bool diffuse_only, const EmissionFocus& focus, VplStats& stats) {
  validate(params);
  stats = VplStats{};
  stats.source = "brsm";
  BrsmSettings s{};
  s.view = view;
  s.focus_center = focus.center;
  s.focus_radius = focus.radius;
  s.seed = seed;
  std::vector<BrsmMap> maps = brsm_maps(lights, params.vpls, params.brsm_maps);
  s.resolution = params.brsm_resolution > 0 ? uint32_t(params.brsm_resolution)
                                            : brsm_auto_resolution(maps, params.brsm_texels_per_vpl);
  stats.resolution = s.resolution;
  s.gbuffer_width = std::max(1u, uint32_t(std::lround(double(view.width) * params.brsm_gbuffer_scale)));
  s.gbuffer_height = std::max(1u, uint32_t(std::lround(double(view.height) * params.brsm_gbuffer_scale)));
  s.gbuffer_samples = uint32_t(params.brsm_gbuffer_samples);
  s.screen_samples = uint32_t(params.brsm_screen_samples);
  s.radius = params.brsm_radius;
  s.power_fraction = params.brsm_power_fraction;
  s.edge_filter = params.brsm_filter ? 1u : 0u;
  s.diffuse_only = diffuse_only ? 1u : 0u;
  s.ray_epsilon = scene_ray_epsilon(scene);
  return {std::move(maps), s};
}

const char* brsm_stage_name(uint32_t stage) {
  switch (stage) {
    case BRSM_STAGE_GBUFFER: return "gbuffer";
    case BRSM_STAGE_TEXELS: return "texels";
    case BRSM_STAGE_FILTER: return "filter";
    case BRSM_STAGE_MIP: return "mip";
    default: return "warp";
  }
}

void brsm_schedule(const BrsmPlan& plan, const std::function<void(uint32_t, uint32_t, uint32_t)>& step,
                   const std::function<void(uint32_t)>& map_done) {
  if (plan.maps.empty()) return;
  step(BRSM_STAGE_GBUFFER, 0, 0);
  const uint32_t top = brsm_top_level(plan.settings.resolution);
  for (uint32_t m = 0; m < uint32_t(plan.maps.size()); ++m) {
    step(BRSM_STAGE_TEXELS, 0, m);
    step(BRSM_STAGE_FILTER, 0, m);
    for (uint32_t level = 1; level <= top; ++level) step(BRSM_STAGE_MIP, level, m);
    step(BRSM_STAGE_WARP, 0, m);
    map_done(m);
  }
}

VplSet generate_brsm_vpls(const Scene& scene, const EmbreeAccel& accel, const LightSampler& lights,
                          const VplParams& params, const ViewParams& view, uint32_t seed, bool diffuse_only,
                          VplStats* stats, const EmissionFocus& focus) {
  auto start = std::chrono::steady_clock::now();
  VplStats local;
  VplStats& st = stats ? *stats : local;
  const PackedLights& packed = lights.packed();
  const BrsmPlan plan = brsm_plan(scene, packed, params, view, seed, diffuse_only, focus, st);
  const std::vector<BrsmMap>& maps = plan.maps;
  const BrsmSettings& s = plan.settings;
  const uint32_t res = s.resolution;
  const uint32_t texel_count = res * res;
  const uint32_t top = brsm_top_level(res);

  std::vector<BrsmGSample> gbuffer(size_t(s.gbuffer_width) * s.gbuffer_height);
  std::vector<BrsmTexel> texels(maps.empty() ? 0 : texel_count);
  std::vector<vec2> mip(maps.empty() ? 0 : brsm_mip_offset(res, top + 1));
  VplSet drawn(size_t(maps.empty() ? 0 : params.vpls));
  const BrsmBuffers buffers{gbuffer.data(), texels.data(), mip.data(), drawn.data()};
  brsm_schedule(
      plan,
      [&](uint32_t stage, uint32_t level, uint32_t m) {
        auto begin = std::chrono::steady_clock::now();
        const BrsmMap& map = maps[m];
        parallel_each(brsm_stage_size(s, map, stage, level), [&](uint32_t i) {
          brsm_stage_step(scene, packed, accel, buffers, s, map, m, stage, level, i);
        });
        add_stage_ms(st, brsm_stage_name(stage),
                     std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count());
      },
      [&](uint32_t) {
        for (const BrsmTexel& t : texels) st.pvpls += luminance(t.intensity) > 0.0f ? 1 : 0;
      });
  VplSet vpls = brsm_finish(drawn, maps.size(), s, params, scene, st);
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return vpls;
}

VplSet brsm_finish(const VplSet& drawn, size_t map_count, const BrsmSettings& settings, const VplParams& params,
                   const Scene& scene, VplStats& stats) {
  VplSet vpls;
  vpls.reserve(drawn.size());
  dvec3 sum(0.0);
  for (const Vpl& v : drawn)
    if (max_component(v.intensity) > 0.0f) {
      vpls.push_back(v);
      sum += dvec3(v.intensity);
    }
  stats.vpls = vpls.size();
  stats.vpls_per_bounce = {vpls.size()};
  stats.intensity_per_bounce = {sum};
  stats.maps = map_count;
  stats.paths = uint64_t(map_count) * settings.resolution * settings.resolution;
  stats.paths_traced = stats.paths;
  stats.rays = map_count == 0 ? 0 : uint64_t(settings.gbuffer_width) * settings.gbuffer_height + stats.paths;
  set_clamp(params, vpls, scene, stats);
  return vpls;
}

}  // namespace sst
