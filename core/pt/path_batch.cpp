#include "core/pt/path_batch.h"

namespace sst {

namespace {

// The live paths that asked for `flag`'s ray: their indices into `traced`, their rays into `rays`.
void gather_rays(const PathState* paths, const std::vector<uint32_t>& active, uint32_t flag, bool shadow,
                 std::vector<uint32_t>& traced, std::vector<Ray>& rays) {
  traced.clear();
  rays.clear();
  for (uint32_t i : active) {
    const PathState& st = paths[i];
    if ((st.flags & flag) == 0u) continue;
    traced.push_back(i);
    Ray ray;
    ray.origin = shadow ? st.shadow.origin : st.origin;
    ray.direction = shadow ? st.shadow.dir : st.dir;
    if (shadow) ray.tmax = st.shadow.tmax;
    rays.push_back(ray);
  }
}

}  // namespace

void trace_path_batch(const RenderContext& ctx, const PathConfig& cfg, RayBatchApi api, PathState* paths, size_t count,
                      PathBatchScratch& scratch) {
  const Scene& scene = ctx.scene;
  const PackedLights& lights = ctx.lights.packed();
  std::vector<uint32_t>& active = scratch.active;
  std::vector<uint32_t>& traced = scratch.traced;
  if (scratch.occluded_size < count) {
    scratch.occluded = std::make_unique<bool[]>(count);
    scratch.occluded_size = count;
  }
  bool* occluded = scratch.occluded.get();

  // The rays of the paths in `active` that asked for one (the camera's or a bounce's), each hit
  // handed to its path by `on_hit`; `active` is then the paths still live.
  auto intersect_stage = [&](auto&& on_hit) {
    gather_rays(paths, active, PATH_RAY_BOUNCE, false, traced, scratch.rays);
    scratch.hits.resize(traced.size());
    ctx.accel.intersect(scratch.rays.data(), traced.size(), scratch.hits.data(), api);
    active.clear();
    for (size_t j = 0; j < traced.size(); ++j) {
      PathState& st = paths[traced[j]];
      on_hit(st, to_bvh_hit(scratch.hits[j]));
      if (st.flags & PATH_ACTIVE) active.push_back(traced[j]);
    }
  };

  active.resize(count);
  for (size_t i = 0; i < count; ++i) active[i] = uint32_t(i);
  intersect_stage([&](PathState& st, const BvhHit& hit) { path_first_hit(scene, st, hit, cfg); });

  while (!active.empty()) {
    for (uint32_t i : active) path_shade(scene, lights, paths[i], cfg);

    gather_rays(paths, active, PATH_RAY_SHADOW, true, traced, scratch.rays);
    ctx.accel.occluded(scratch.rays.data(), traced.size(), occluded, api);
    // Every live path takes its light sample's share: those with a shadow ray by its answer, then
    // those left waiting (PATH_NEE without a ray) as unoccluded.
    for (size_t j = 0; j < traced.size(); ++j) path_shadow_result(paths[traced[j]], occluded[j]);
    for (uint32_t i : active) path_shadow_result(paths[i], false);

    intersect_stage([&](PathState& st, const BvhHit& hit) { path_bounce_hit(scene, lights, st, hit, cfg); });
  }
}

void trace_tile_paths(const RenderContext& ctx, const PathConfig& cfg, const Tile& tile, RayCounters& counters,
                      const PathFinish& finish) {
  const int spp = ctx.options.spp;
  const size_t total = size_t(tile.pixels()) * size_t(spp);
  // Path `index` of the tile: pixel index / spp (row-major in the tile), sample index % spp.
  auto begin = [&](size_t index, Ray& camera_ray) {
    const int p = int(index / size_t(spp)), i = int(index % size_t(spp));
    const int x = tile.x0 + p % tile.width(), y = tile.y0 + p / tile.width();
    PixelSampler sampler = pixel_sampler(ctx.options.seed, uint32_t(y) * uint32_t(ctx.width) + uint32_t(x), uint32_t(i));
    vec2 jitter = pixel_sampler_get2d(sampler);
    camera_ray = ctx.camera.generate(float(x) + jitter.x, float(y) + jitter.y);
    return path_begin(camera_ray.origin, camera_ray.direction, sampler);
  };
  auto end = [&](size_t index, const Ray& camera_ray, PathState& st) {
    counters.primary_rays += st.counters.primary_rays;
    counters.shadow_rays += st.counters.shadow_rays;
    counters.bounce_rays += st.counters.bounce_rays;
    ++counters.samples;
    finish(int(index / size_t(spp)), int(index % size_t(spp)), camera_ray, st);
  };

  const size_t batch = size_t(ctx.options.path_batch);
  if (batch == 0) {
    for (size_t index = 0; index < total; ++index) {
      Ray camera_ray;
      PathState st = begin(index, camera_ray);
      trace_path_state(ctx.scene, ctx.lights.packed(), ctx.accel, st, cfg);
      end(index, camera_ray, st);
    }
    return;
  }
  // One scratch per thread, reused by every tile it renders: a batch's paths are a few hundred
  // bytes each, too many to allocate per tile.
  thread_local PathBatchScratch scratch;
  const RayBatchApi api = parse_ray_batch_api(ctx.options.batch_rays);
  for (size_t first = 0; first < total; first += batch) {
    const size_t n = std::min(batch, total - first);
    scratch.paths.resize(n);
    scratch.camera_rays.resize(n);
    for (size_t j = 0; j < n; ++j) scratch.paths[j] = begin(first + j, scratch.camera_rays[j]);
    trace_path_batch(ctx, cfg, api, scratch.paths.data(), n, scratch);
    for (size_t j = 0; j < n; ++j) end(first + j, scratch.camera_rays[j], scratch.paths[j]);
  }
}

}  // namespace sst
