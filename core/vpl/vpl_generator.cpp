#include "core/vpl/vpl_generator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <string>

#include "core/shading/surface.h"
#include "core/util/memory.h"
#include "core/vpl/vpl_clamp.h"

namespace sst {
namespace {

// Paths are traced in fixed chunks of consecutive indices, each chunk into its own buffers, and
// the chunks are concatenated in index order: the output never depends on which thread ran what.
constexpr uint64_t kPathsPerChunk = 256;
// vpls * kMaxPathsPerVpl path indices must fit the 32-bit HashRng counter.
constexpr int kMaxVpls = 50'000'000;
// Freed chunk memory beyond this goes back to the kernel (generate_vpls).
constexpr size_t kReleaseBytes = size_t(32) << 20;

struct Chunk {
  std::vector<Vpl> vpls;           // path order, then hit order
  std::vector<uint16_t> hit;       // hit index of each VPL (0: first hit)
  std::vector<uint32_t> path_end;  // per path of the chunk: one past its last VPL in `vpls`
  uint64_t rays = 0;
};

void deposit_vpl(Chunk& out, int hit, vec3 position, vec3 normal, vec3 intensity) {
  out.vpls.push_back({position, normal, intensity});
  out.hit.push_back(uint16_t(hit));
}

}  // namespace
}  // namespace sst

#define VPL_CTX_PARAM Chunk &out,
#define VPL_CTX out,
#define VPL_DEPOSIT(deposit, hit, position, normal, intensity) deposit_vpl(out, hit, position, normal, intensity)
#include "core/vpl/light_path.h"

namespace sst {
namespace {

struct Tracer {
  const Scene& scene;
  const EmbreeAccel& accel;
  const LightSampler& lights;
  const VplParams& params;
  uint32_t seed;
  bool diffuse_only;
  EmissionFocus focus;

  // One light path (core/vpl/light_path.h); appends its VPLs to `out`.
  void trace(uint32_t path, Chunk& out) const {
    uvec2 r = trace_light_path(scene, lights.packed(), accel, out, seed, path, params.vpl_max_bounces,
                               params.vpl_min_bounces, diffuse_only, focus, params.focus_bounces);
    out.rays += r.y;
  }

  void trace_chunk(uint64_t first_path, uint64_t end_path, Chunk& chunk) const {
    chunk.path_end.reserve(size_t(end_path - first_path));
    for (uint64_t p = first_path; p < end_path; ++p) {
      trace(uint32_t(p), chunk);
      chunk.path_end.push_back(uint32_t(chunk.vpls.size()));
    }
  }
};

// Paths for the next batch: from the VPLs per path seen so far, the remaining count plus 1% and
// a chunk (a shortfall costs one more, small, batch); a first pilot batch is small, so a scene
// with many VPLs per path is not overshot by much. Any batching gives the same set; this only
// bounds the paths traced past the last one used.
uint64_t next_batch(uint64_t remaining, uint64_t deposited, uint64_t traced) {
  if (traced == 0) return std::clamp<uint64_t>(remaining / 16, kPathsPerChunk, 64 * kPathsPerChunk);
  if (deposited == 0) return 4 * traced;
  double per_path = double(deposited) / double(traced);
  return uint64_t(1.01 * double(remaining) / per_path) + kPathsPerChunk;
}

// Traces chunks of paths in parallel until `target` VPLs exist or `max_paths` were traced.
std::vector<Chunk> trace_chunks(const Tracer& tracer, uint64_t target, uint64_t max_paths) {
  std::vector<Chunk> chunks;
  uint64_t deposited = 0, traced = 0;
  while (deposited < target && traced < max_paths) {
    uint64_t batch = std::min(next_batch(target - deposited, deposited, traced), max_paths - traced);
    size_t first = chunks.size();
    size_t count = size_t((batch + kPathsPerChunk - 1) / kPathsPerChunk);
    chunks.resize(first + count);
    tbb::parallel_for(tbb::blocked_range<size_t>(first, first + count, 1), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t c = r.begin(); c != r.end(); ++c) {
        uint64_t begin = uint64_t(c) * kPathsPerChunk;
        tracer.trace_chunk(begin, std::min(begin + kPathsPerChunk, max_paths), chunks[c]);
      }
    });
    for (size_t c = first; c < chunks.size(); ++c) deposited += chunks[c].vpls.size();
    traced = std::min(uint64_t(chunks.size()) * kPathsPerChunk, max_paths);
  }
  return chunks;
}

// Concatenates the chunks up to the path that completes `target` VPLs (dropping its surplus),
// divides every intensity by the number of paths that took part, and fills the statistics.
VplSet assemble(const std::vector<Chunk>& chunks, uint64_t target, uint64_t max_paths, int max_hits,
                VplStats& stats) {
  // Sized once: growing by doubling would hold up to three times the set at a moment when every
  // chunk is still alive, which was the peak memory of a run without a light tree.
  uint64_t deposited = 0;
  for (const Chunk& chunk : chunks) deposited += chunk.vpls.size();
  VplSet out;
  std::vector<uint16_t> hits;
  out.reserve(size_t(std::min(deposited, target)));
  hits.reserve(out.capacity());
  uint64_t paths = 0;
  for (size_t c = 0; c < chunks.size() && out.size() < target; ++c) {
    const Chunk& chunk = chunks[c];
    uint64_t need = target - out.size();
    size_t take = chunk.vpls.size();
    paths = uint64_t(c) * kPathsPerChunk + chunk.path_end.size();
    if (take >= need) {
      take = size_t(need);
      size_t j = size_t(std::lower_bound(chunk.path_end.begin(), chunk.path_end.end(), uint32_t(need)) -
                        chunk.path_end.begin());
      paths = uint64_t(c) * kPathsPerChunk + j + 1;
    }
    out.insert(out.end(), chunk.vpls.begin(), chunk.vpls.begin() + take);
    hits.insert(hits.end(), chunk.hit.begin(), chunk.hit.begin() + take);
  }
  if (out.size() < target) paths = std::min(uint64_t(chunks.size()) * kPathsPerChunk, max_paths);
  stats.paths = paths;
  stats.path_limit_reached = max_paths > 0 && out.size() < target && paths >= max_paths;
  stats.vpls_per_bounce.assign(size_t(max_hits), 0);
  stats.intensity_per_bounce.assign(size_t(max_hits), dvec3(0.0));
  if (paths == 0) return out;
  const float inv_paths = float(1.0 / double(paths));
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].intensity *= inv_paths;
    ++stats.vpls_per_bounce[hits[i]];
    stats.intensity_per_bounce[hits[i]] += dvec3(out[i].intensity);
  }
  return out;
}

}  // namespace

void validate(const VplParams& p) {
  if (p.vpls < 1) throw Error("vpls must be >= 1 (got " + std::to_string(p.vpls) + ")");
  if (p.vpls > kMaxVpls) throw Error("vpls must be <= " + std::to_string(kMaxVpls) + " (got " + std::to_string(p.vpls) + ")");
  if (p.vpl_max_bounces < 1) throw Error("vpl_max_bounces must be >= 1 (got " + std::to_string(p.vpl_max_bounces) + ")");
  if (p.vpl_max_bounces > 1024) throw Error("vpl_max_bounces must be <= 1024 (got " + std::to_string(p.vpl_max_bounces) + ")");
  if (p.vpl_min_bounces < 0) throw Error("vpl_min_bounces must be >= 0 (got " + std::to_string(p.vpl_min_bounces) + ")");
  if (!(p.clamp_fraction >= 0.0f) || !std::isfinite(p.clamp_fraction))
    throw Error("clamp_fraction must be a finite number >= 0 (got " + std::to_string(p.clamp_fraction) + ")");
  if (!(p.directional_focus >= 0.0f) || !std::isfinite(p.directional_focus))
    throw Error("directional_focus must be a finite number >= 0 (got " + std::to_string(p.directional_focus) + ")");
  if (!(p.focus_bounces >= 0.0f && p.focus_bounces < 1.0f))
    throw Error("focus_bounces must be in [0, 1) (got " + std::to_string(p.focus_bounces) + ")");
  if (p.vpl_source != "paths" && p.vpl_source != "brsm")
    throw Error("vpl_source must be paths or brsm (got '" + p.vpl_source + "')");
  if (p.brsm_resolution != 0 &&
      (p.brsm_resolution < 2 || p.brsm_resolution > 4096 || (p.brsm_resolution & (p.brsm_resolution - 1)) != 0))
    throw Error("brsm_resolution must be 0 or a power of two in 2..4096 (got " + std::to_string(p.brsm_resolution) +
                ")");
  if (!(p.brsm_texels_per_vpl > 0.0f && p.brsm_texels_per_vpl <= 1e6f))
    throw Error("brsm_texels_per_vpl must be in (0, 1e6] (got " + std::to_string(p.brsm_texels_per_vpl) + ")");
  if (p.brsm_maps < 1 || p.brsm_maps > 4096)
    throw Error("brsm_maps must be in 1..4096 (got " + std::to_string(p.brsm_maps) + ")");
  if (!(p.brsm_gbuffer_scale > 0.0f && p.brsm_gbuffer_scale <= 1.0f))
    throw Error("brsm_gbuffer_scale must be in (0, 1] (got " + std::to_string(p.brsm_gbuffer_scale) + ")");
  if (p.brsm_gbuffer_samples < 0 || p.brsm_gbuffer_samples > 1024)
    throw Error("brsm_gbuffer_samples must be in 0..1024 (got " + std::to_string(p.brsm_gbuffer_samples) + ")");
  if (p.brsm_screen_samples < 0 || p.brsm_screen_samples > 1024)
    throw Error("brsm_screen_samples must be in 0..1024 (got " + std::to_string(p.brsm_screen_samples) + ")");
  if (!(p.brsm_radius > 0.0f) || !std::isfinite(p.brsm_radius))
    throw Error("brsm_radius must be a finite number > 0 (got " + std::to_string(p.brsm_radius) + ")");
  if (!(p.brsm_power_fraction >= 0.0f && p.brsm_power_fraction <= 1.0f))
    throw Error("brsm_power_fraction must be in [0, 1] (got " + std::to_string(p.brsm_power_fraction) + ")");
  if (p.clamp_relative_to != "camera_distance" && p.clamp_relative_to != "vpl_bounds")
    throw Error("clamp_relative_to must be camera_distance or vpl_bounds (got '" + p.clamp_relative_to + "')");
}

void set_clamp(const VplParams& p, const VplSet& vpls, const Scene& scene, VplStats& st) {
  const bool per_depth = p.clamp_relative_to == "camera_distance";
  st.clamp_distance = per_depth ? 0.0f : vpl_clamp_distance(p.clamp_fraction, vpls, scene);
  st.clamp_per_depth = per_depth ? p.clamp_fraction : 0.0f;
}

void add_stage_ms(VplStats& stats, const char* stage, double ms) {
  for (auto& [name, total] : stats.stage_ms)
    if (name == stage) {
      total += ms;
      return;
    }
  stats.stage_ms.emplace_back(stage, ms);
}

nlohmann::json to_json(const VplStats& s) {
  nlohmann::json intensity = nlohmann::json::array();
  for (const dvec3& i : s.intensity_per_bounce) intensity.push_back({i.x, i.y, i.z});
  nlohmann::json j = {{"source", s.source},
                      {"paths", s.paths},
                      {"paths_traced", s.paths_traced},
                      {"vpls", s.vpls},
                      {"rays", s.rays},
                      {"ms", s.ms},
                      {"path_limit_reached", s.path_limit_reached},
                      {"clamp_distance", s.clamp_distance},
                      {"clamp_per_depth", s.clamp_per_depth},
                      {"vpls_per_bounce", s.vpls_per_bounce},
                      {"intensity_per_bounce", intensity}};
  if (s.source == "brsm") {
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& [name, ms] : s.stage_ms) stages[name] = ms;
    j["maps"] = s.maps;
    j["resolution"] = s.resolution;
    j["pvpls"] = s.pvpls;
    j["stage_ms"] = stages;
  }
  return j;
}

VplSet generate_vpls(const Scene& scene, const EmbreeAccel& accel, const LightSampler& lights,
                     const VplParams& params, uint32_t seed, bool diffuse_only, VplStats* stats,
                     const EmissionFocus& focus) {
  validate(params);
  auto start = std::chrono::steady_clock::now();
  VplStats local;
  VplStats& st = stats ? *stats : local;
  st = VplStats{};
  const uint64_t target = uint64_t(params.vpls);
  const uint64_t max_paths = lights.empty() ? 0 : kMaxPathsPerVpl * target;
  Tracer tracer{scene, accel, lights, params, seed, diffuse_only, focus};
  std::vector<Chunk> chunks = trace_chunks(tracer, target, max_paths);
  VplSet vpls = assemble(chunks, target, max_paths, params.vpl_max_bounces, st);
  st.paths_traced = std::min(uint64_t(chunks.size()) * kPathsPerChunk, max_paths);
  for (const Chunk& c : chunks) st.rays += c.rays;
  // The chunks are many small buffers in the threads' malloc arenas, which keep them resident
  // once freed; a light tree's arrays, allocated next, are too large to reuse them. Handing them
  // back costs page faults later (5 ms of 28 at 100k VPLs), so only for sets whose memory matters:
  // at 1M VPLs it lowers the peak of an sst render by 35 bytes per VPL.
  size_t chunk_bytes = 0;
  for (const Chunk& c : chunks)
    chunk_bytes += c.vpls.capacity() * sizeof(Vpl) + c.hit.capacity() * sizeof(uint16_t) +
                   c.path_end.capacity() * sizeof(uint32_t);
  chunks = {};
  if (chunk_bytes >= kReleaseBytes) release_free_memory();
  st.vpls = vpls.size();
  set_clamp(params, vpls, scene, st);
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return vpls;
}

}  // namespace sst
