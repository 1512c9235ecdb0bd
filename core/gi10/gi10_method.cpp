#include "core/gi10/gi10_method.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include "core/pt/path_tracer.h"
#include "core/render/camera.h"
#include "core/render/view_length.h"
#include "core/util/byte_io.h"
#include "core/util/zero_runs.h"

#include "core/gi10/gi10_cpu.h"

namespace sst {

static_assert(sizeof(glsl::Gi10Frame) == 304, "Gi10Frame must match its std430 layout");
static_assert(sizeof(glsl::Gi10Pixel) == 32, "Gi10Pixel must match its std430 layout");
static_assert(sizeof(glsl::Gi10Ray) == 128, "Gi10Ray must match its std430 layout");

namespace {

const char* kStageNames[] = {"gbuffer", "purge",  "reproject", "spawn",       "sample",      "trace",
                             "shade",   "update", "resolve",   "blend",       "mask_mip",    "filter",
                             "project", "interpolate", "denoise_reproject", "blur_mask", "filter_gi",
                             "copy_probes", "feedback", "empty_tiles", "list_count", "list_scan",
                             "list_compact", "patch", "store_reservoir", "side_lookup", "side_allocate",
                             "side_reorder"};
static_assert(sizeof(kStageNames) / sizeof(kStageNames[0]) == GI10_STAGES);

// The paper's three timing buckets (docs/design/gi10.md, the record); the G-buffer, feedback
// image and direct pass apart.
const char* bucket_of(uint32_t stage) {
  switch (stage) {
    case GI10_STAGE_TRACE:
    case GI10_STAGE_SHADE: return "ray_tracing";
    case GI10_STAGE_STORE_RESERVOIR: return "caching_sampling";
    case GI10_STAGE_PROJECT:
    case GI10_STAGE_INTERPOLATE:
    case GI10_STAGE_DENOISE_REPROJECT:
    case GI10_STAGE_BLUR_MASK:
    case GI10_STAGE_FILTER_GI: return "interpolate_denoise";
    case GI10_STAGE_GBUFFER: return "gbuffer";
    case GI10_STAGE_FEEDBACK: return "compose";
    default: return "caching_sampling";
  }
}

std::string choice(const std::string& field, const std::string& value, std::initializer_list<const char*> allowed) {
  for (const char* a : allowed)
    if (value == a) return value;
  std::string list;
  for (const char* a : allowed) list += (list.empty() ? "" : "|") + std::string(a);
  throw Error("gi10 parameter " + field + ": '" + value + "' is not one of " + list);
}

// The CPU executor: each stage a oneTBB loop over its elements, on vectors.
class Gi10Cpu final : public Gi10Executor {
 public:
  void allocate(const Gi10Sizes& s) override {
    uint64_t px = s.pixels(), nt = s.tiles(), ns = s.spawns(), t = s.hash_tiles;
    pixels_.assign(2 * px, glsl::Gi10Pixel{});
    mask_.assign(2 * uint64_t(s.mask_total), kGiNoProbe);
    radiance_.assign(s.radiance_entries(), vec4(0.0f));
    sh_.assign(2 * nt * 9, vec4(0.0f));
    spawn_.assign(s.spawn_words(), 0u);
    rays_.assign(ns * 64, glsl::Gi10Ray{});
    hash_.assign(s.hash_words(), 0u);
    values_.assign(t * kGiCellsPerTile, vec4(0.0f));
    accum_.assign(t * 64 * kGiAccumWords, 0u);
    emission_.assign(px, vec4(0.0f));
    denoise_.assign(3 * px, vec4(0.0f));
    aux_.assign(3 * px, vec4(0.0f));
    feedback_.assign(px, vec4(0.0f));
    counters_.assign(GI10_COUNTERS, 0u);
    output_.assign(px, vec4(0.0f));
    ray_reservoirs_.assign(s.ray_reservoirs(), RestirReservoir{});
    slot_reservoirs_.assign(s.slot_entries(), RestirReservoir{});
    slot_surfaces_.assign(s.slot_entries(), RestirSurface{});
    b_.frame = &frame_;
    b_.pixels = pixels_.data();
    b_.mask = mask_.data();
    b_.radiance = radiance_.data();
    b_.sh = sh_.data();
    b_.spawn = spawn_.data();
    b_.rays = rays_.data();
    b_.hash = hash_.data();
    b_.values = values_.data();
    b_.accum = accum_.data();
    b_.emission = emission_.data();
    b_.denoise = denoise_.data();
    b_.aux = aux_.data();
    b_.feedback = feedback_.data();
    b_.counters = counters_.data();
    b_.output = output_.data();
    b_.ray_reservoirs = ray_reservoirs_.data();
    b_.slot_reservoirs = slot_reservoirs_.data();
    b_.slot_surfaces = slot_surfaces_.data();
  }
  void begin_frame(const RenderContext& context, const glsl::Gi10Frame& frame) override {
    context_ = &context;
    frame_ = frame;
  }
  double run(uint32_t stage, uint32_t pass, uint32_t count) override {
    auto start = std::chrono::steady_clock::now();
    const RenderContext& c = *context_;
    const PackedLights& lights = c.lights.packed();
    const Scene& scene = c.scene;
    const EmbreeAccel& accel = c.accel;
    const Gi10Buffers& gi = b_;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, 64),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                        for (uint32_t i = r.begin(); i != r.end(); ++i)
                          gi10_stage(scene, lights, accel, gi, stage, pass, i);
                      });
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  void clear_counters() override { std::fill(counters_.begin(), counters_.end(), 0u); }
  std::vector<uint32_t> counters() override { return counters_; }
  void read_irradiance(std::vector<vec4>& denoised, std::vector<vec4>& raw) override {
    denoised = output_;
    raw.assign(denoise_.begin(), denoise_.begin() + ptrdiff_t(output_.size()));
  }
  void read_pixels(std::vector<glsl::Gi10Pixel>& pixels) override {
    size_t n = output_.size();
    size_t first = (frame_.frame & 1u) * n;
    pixels.assign(pixels_.begin() + ptrdiff_t(first), pixels_.begin() + ptrdiff_t(first + n));
  }
  void write_feedback(const std::vector<vec4>& image) override { feedback_ = image; }
  FrameOutput direct(const RenderContext& context, StageTimer& timer) override {
    PathTracerParams p;
    p.max_bounces = 0;
    return PathTracer(p).render(context, timer);  // as every VPL method's direct pass
  }
  std::vector<std::span<const uint8_t>> buffers() const override { return byte_views<const uint8_t>(*this); }
  std::vector<std::span<uint8_t>> buffers() override { return byte_views<uint8_t>(*this); }

 private:
  // The buffers of `self` (const or not) in gi10_buffers.h's order, VulkanGi10's, as bytes.
  template <class Byte, class Self>
  static std::vector<std::span<Byte>> byte_views(Self& self) {
    std::vector<std::span<Byte>> out;
    auto view = [&](auto& v) { out.emplace_back(reinterpret_cast<Byte*>(v.data()), v.size() * sizeof(v[0])); };
    view(self.pixels_), view(self.emission_), view(self.mask_), view(self.radiance_), view(self.sh_);
    view(self.spawn_), view(self.rays_), view(self.hash_), view(self.values_), view(self.accum_);
    view(self.denoise_), view(self.aux_), view(self.feedback_), view(self.counters_), view(self.output_);
    view(self.ray_reservoirs_), view(self.slot_reservoirs_), view(self.slot_surfaces_);
    return out;
  }

  const RenderContext* context_ = nullptr;
  glsl::Gi10Frame frame_{};
  std::vector<glsl::Gi10Pixel> pixels_;
  std::vector<uint32_t> mask_, spawn_, hash_, accum_, counters_;
  std::vector<vec4> radiance_, sh_, values_, emission_, denoise_, aux_, feedback_, output_;
  std::vector<glsl::Gi10Ray> rays_;
  std::vector<RestirReservoir> ray_reservoirs_, slot_reservoirs_;
  std::vector<RestirSurface> slot_surfaces_;
  Gi10Buffers b_;
};

// tan(fov_y * px * max(1 / H, H / W^2)): the angle `px` pixels subtend (the paper's Algorithm 6).
float pixel_angle_tan(const glsl::ViewParams& view, float px) {
  double fov_y = 2.0 * std::atan(double(view.tan_half_y));
  double w = double(view.width), h = double(view.height);
  return float(std::tan(fov_y * px * std::max(1.0 / h, h / (w * w))));
}

}  // namespace

void validate(const Gi10Params& p) { resolve_gi10(p); }

Gi10Resolved resolve_gi10(const Gi10Params& p) {
  bool caps = choice("preset", p.preset, {"fair", "capsaicin"}) == "capsaicin";
  auto pick = [&](const char* field, const std::string& v, std::initializer_list<const char*> allowed,
                  const char* fair, const char* capsaicin) {
    std::string c = choice(field, v, allowed);
    return c == "auto" ? std::string(caps ? capsaicin : fair) : c;
  };
  Gi10Resolved r;
  if (p.feedback) r.flags |= GI10_FEEDBACK;
  if (pick("probe_emission", p.probe_emission, {"auto", "on", "off"}, "off", "on") == "on") r.flags |= GI10_PROBE_EMISSION;
  if (pick("backup", p.backup, {"auto", "mean", "spread"}, "mean", "spread") == "mean") r.flags |= GI10_BACKUP_MEAN;
  r.sh_weight = pick("sh_weight", p.sh_weight, {"auto", "solid_angle", "capsaicin"}, "solid_angle", "capsaicin") ==
                        "capsaicin"
                    ? 0.125f
                    : float(2.0 * M_PI / 64.0);
  if (pick("blur_mask", p.blur_mask, {"auto", "full", "capsaicin"}, "full", "capsaicin") == "capsaicin")
    r.flags |= GI10_BLUR_MASK_CAPSAICIN;
  r.capsaicin_cells = pick("cell_base", p.cell_base, {"auto", "scene", "capsaicin"}, "scene", "capsaicin") == "capsaicin";
  if (p.short_ray_bit) r.flags |= GI10_SHORT_RAY_BIT;
  if (p.bypass) r.flags |= GI10_BYPASS;
  if (p.probe_filter) r.flags |= GI10_PROBE_FILTER;
  if (p.guiding) r.flags |= GI10_GUIDING;
  if (p.irradiance_denoiser) r.flags |= GI10_DENOISE;
  if (p.hysteresis) r.flags |= GI10_HYSTERESIS;
  if (choice("texel_estimate", p.texel_estimate, {"fill", "expected"}) == "expected") r.flags |= GI10_TEXEL_EXPECTED;
  if (p.cache_lookup) r.flags |= GI10_CACHE_LOOKUP;
  if (choice("irradiance_basis", p.irradiance_basis, {"sh", "texels"}) == "texels") r.flags |= GI10_IRRADIANCE_TEXELS;
  if (p.world_restir) r.flags |= GI10_WORLD_RESTIR;
  if (choice("world_restir_combine", p.world_restir_combine, {"unbiased", "biased"}) == "unbiased")
    r.flags |= GI10_WORLD_RESTIR_UNBIASED;
  if (choice("cache_shading", p.cache_shading, {"light", "path"}) == "path") r.flags |= GI10_CACHE_PATHS;
  r.side_cache = pick("side_cache", p.side_cache, {"auto", "on", "off"}, "off", "on") == "on";
  if (p.cache_path_bounces < 1 || p.cache_path_bounces > 64) throw Error("gi10 parameter cache_path_bounces must be in 1..64");
  if (p.world_restir_candidates < 1 || p.world_restir_candidates > 64)
    throw Error("gi10 parameter world_restir_candidates must be in 1..64");
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0)) throw Error(std::string("gi10 parameter ") + name + " must be > 0 (got " + std::to_string(v) + ")");
  };
  if (p.cache_warmup_frames < 0 || p.cache_warmup_frames > 100000) throw Error("gi10 parameter cache_warmup_frames must be in 0..100000");
  positive("hash_cell_px", p.hash_cell_px);
  positive("min_cell_ratio", p.min_cell_ratio);
  if (p.hash_buckets_log2 < 1 || p.hash_buckets_log2 > 16) throw Error("gi10 parameter hash_buckets_log2 must be in 1..16");
  if (p.tiles_per_bucket_log2 < 0 || p.tiles_per_bucket_log2 > 6)
    throw Error("gi10 parameter tiles_per_bucket_log2 must be in 0..6");
  if (p.max_samples < 1 || p.max_samples > 1 << 20) throw Error("gi10 parameter max_samples must be in 1..1048576");
  if (p.cell_px_height < 0) throw Error("gi10 parameter cell_px_height must be >= 0");
  if (p.tile_decay < 1) throw Error("gi10 parameter tile_decay must be >= 1");
  for (auto [name, v] : {std::pair{"reproject_normal", p.reproject_normal}, {"feedback_normal", p.feedback_normal}})
    if (!(v >= -1.0f && v <= 1.0f)) throw Error(std::string("gi10 parameter ") + name + " must be in -1..1");
  positive("feedback_depth", p.feedback_depth);
  if (!(p.filter_angle >= 0.0f && p.filter_angle <= 1.0f)) throw Error("gi10 parameter filter_angle must be in 0..1");
  if (!(p.interpolation_jitter >= 0.0f && p.interpolation_jitter <= 1024.0f))
    throw Error("gi10 parameter interpolation_jitter must be in 0..1024");
  if (!(p.denoise_history >= 0.5f && p.denoise_history <= 1e6f)) throw Error("gi10 parameter denoise_history must be in 0.5..1e6");
  return r;
}

uint64_t Gi10Sizes::list_blocks() const { return (spawns() + kGiBlock - 1) / kGiBlock + (tiles() + kGiBlock - 1) / kGiBlock; }
uint64_t Gi10Sizes::spawn_words() const {
  const uint64_t lists = 3 * spawns() + 2 * tiles() + list_blocks() + 2;
  if (side_slots == 0) return lists;
  const uint64_t side_blocks = (side_slots + kGiBlock - 1) / kGiBlock;
  return lists + 4 * uint64_t(side_slots) + tiles() * kGiSideListLength + 2 * spawns() + 2 * side_blocks;
}
uint64_t Gi10Sizes::radiance_entries() const { return 2 * tiles() * 64 + 66 * uint64_t(side_slots); }
uint64_t Gi10Sizes::hash_words() const { return 2 * uint64_t(hash_tiles) + 3 * uint64_t(reservoir_slots); }
uint64_t Gi10Sizes::ray_reservoirs() const { return reservoir_slots > 0 ? spawns() * 64 : 1; }
uint64_t Gi10Sizes::slot_entries() const { return 2 * std::max<uint64_t>(reservoir_slots, 1); }

glm::uvec2 gi10_mask_level_size(const Gi10Sizes& sizes, uint32_t level) {
  glm::uvec2 size(sizes.tiles_x, sizes.tiles_y);
  for (uint32_t i = 0; i < level; ++i) size = glm::max((size + 1u) / 2u, glm::uvec2(1u));
  return size;
}

Gi10Sizes gi10_sizes(int width, int height, const Gi10Params& params) {
  Gi10Sizes s;
  s.width = uint32_t(width);
  s.height = uint32_t(height);
  s.tiles_x = (s.width + 7) / 8;
  s.tiles_y = (s.height + 7) / 8;
  s.spawn_x = (s.width + 15) / 16;
  s.spawn_y = (s.height + 15) / 16;
  s.mask_levels = 1;
  s.mask_total = s.tiles_x * s.tiles_y;
  for (glm::uvec2 size(s.tiles_x, s.tiles_y); size.x > 1 || size.y > 1; ++s.mask_levels) {
    size = gi10_mask_level_size(s, s.mask_levels);
    s.mask_total += size.x * size.y;
  }
  s.hash_tiles = (1u << params.hash_buckets_log2) << params.tiles_per_bucket_log2;
  s.reservoir_slots = params.world_restir ? s.hash_tiles : 0u;
  s.side_slots = resolve_gi10(params).side_cache ? uint32_t(s.tiles()) : 0u;
  return s;
}

Gi10Renderer::Gi10Renderer(const Gi10Params& params) : params_(params), resolved_(resolve_gi10(params)) {}

FrameOutput Gi10Renderer::render(const RenderContext& context, Gi10Executor& executor, StageTimer& timer) {
  Gi10Sizes sizes = gi10_sizes(context.width, context.height, params_);
  if (context.frame == 0 || !started_ || !(sizes == sizes_)) {
    sizes_ = sizes;
    executor.allocate(sizes_);
    started_ = true;
    frame_ = 0;
    view_length_ = 0.0f;
    // Warm-up: the caches fill over frames, at the first view, with fresh random numbers each frame.
    StageTimer discard;
    RenderOptions options = context.options;
    for (int i = 0; i < params_.cache_warmup_frames; ++i) {
      options.seed = context.options.seed ^ (0x9E3779B9u * uint32_t(i + 1));
      RenderContext c{context.scene, context.accel,  context.lights, context.camera, options,
                      context.width, context.height, true,           0};
      render_one(c, executor, discard, true);
    }
  }
  return render_one(context, executor, timer, false);
}

namespace {
// The layout sizes are part of the magic: a build whose structs differ cannot misread the bytes.
struct Gi10StateHeader {
  char magic[8] = {'S', 'S', 'T', 'G', 'I', '1', '0', '\0'};
  uint32_t sizes_bytes = sizeof(Gi10Sizes);
  uint32_t view_bytes = sizeof(glsl::ViewParams);
  uint32_t frame = 0;
  float view_length = 0.0f;
  uint64_t buffers = 0;
};
}  // namespace

std::vector<uint8_t> Gi10Renderer::save(const Gi10Executor& executor) const {
  if (!started_) return {};
  Gi10StateHeader h;
  h.frame = frame_;
  h.view_length = view_length_;
  const std::vector<std::span<const uint8_t>> buffers = executor.buffers();
  h.buffers = buffers.size();
  std::vector<uint8_t> out;
  append_bytes(out, &h);
  append_bytes(out, &sizes_);
  append_bytes(out, &previous_view_);
  // The caches are mostly empty hash tiles: their zero words are stored as counts.
  for (std::span<const uint8_t> b : buffers) {
    const uint64_t n = b.size();
    append_bytes(out, &n);
    zero_runs_encode(b, out);
  }
  return out;
}

void Gi10Renderer::restore(std::span<const uint8_t> bytes, Gi10Executor& executor) {
  if (bytes.empty()) {
    started_ = false;
    return;
  }
  ByteReader r(bytes, "not a gi10 state of this build");
  const Gi10StateHeader h = r.read<Gi10StateHeader>();
  const Gi10StateHeader expected;
  if (std::memcmp(h.magic, expected.magic, sizeof h.magic) != 0 || h.sizes_bytes != expected.sizes_bytes ||
      h.view_bytes != expected.view_bytes)
    throw r.bad("another format");
  const Gi10Sizes sizes = r.read<Gi10Sizes>();
  const glsl::ViewParams previous_view = r.read<glsl::ViewParams>();
  executor.allocate(sizes);
  const std::vector<std::span<uint8_t>> buffers = executor.buffers();
  if (h.buffers != buffers.size())
    throw r.bad(std::to_string(h.buffers) + " buffers, expected " + std::to_string(buffers.size()));
  for (std::span<uint8_t> b : buffers) {
    if (r.read<uint64_t>() != b.size()) throw r.bad("a buffer does not match the sizes it was saved at");
    try {
      r.skip(zero_runs_decode(r.rest(), b));
    } catch (const Error& e) {
      throw r.bad(e.what());
    }
  }
  if (r.left() != 0) throw r.bad("its size does not match its buffers");
  sizes_ = sizes;
  previous_view_ = previous_view;
  frame_ = h.frame;
  view_length_ = h.view_length;
  started_ = true;
}

FrameOutput Gi10Renderer::render_one(const RenderContext& context, Gi10Executor& executor, StageTimer& timer,
                                     bool warmup) {
  StageTimer direct_timer;
  FrameOutput out = executor.direct(context, direct_timer);
  double direct_ms = 0.0;
  for (const auto& [stage, ms] : direct_timer.stages()) direct_ms += ms;
  timer.add("direct", direct_ms);
  glsl::Gi10Frame f{};
  f.view = view_params(context.camera, context.width, context.height, context.options.seed);
  f.previous_view = frame_ == 0 ? f.view : previous_view_;
  f.width = sizes_.width;
  f.height = sizes_.height;
  f.tiles_x = sizes_.tiles_x;
  f.tiles_y = sizes_.tiles_y;
  f.spawn_x = sizes_.spawn_x;
  f.spawn_y = sizes_.spawn_y;
  f.mask_levels = sizes_.mask_levels;
  f.frame = frame_;
  f.seed = context.options.seed;
  f.flags = resolved_.flags;
  f.has_history = frame_ > 0 ? 1u : 0u;
  f.diffuse_only = context.options.diffuse_only ? 1u : 0u;
  uvec2 j16 = gi_spawn_jitter(frame_, 16u), j8 = gi_spawn_jitter(frame_, 8u);
  f.jitter16 = {j16.x, j16.y};
  f.jitter8 = {j8.x, j8.y};
  f.scene_epsilon = context.accel.scene_epsilon();
  f.k_probe = pixel_angle_tan(f.view, 8.0f);
  float cell_px = params_.hash_cell_px;
  if (params_.cell_px_height > 0) cell_px *= float(context.height) / float(params_.cell_px_height);
  f.k_hash = pixel_angle_tan(f.view, cell_px);
  f.num_buckets = 1u << params_.hash_buckets_log2;
  f.tiles_per_bucket = 1u << params_.tiles_per_bucket_log2;
  f.max_samples = float(params_.max_samples);
  f.tile_decay = uint32_t(params_.tile_decay);
  f.sh_weight = resolved_.sh_weight;
  f.reproject_normal = params_.reproject_normal;
  f.feedback_normal = params_.feedback_normal;
  f.feedback_depth = params_.feedback_depth;
  f.filter_angle = float(std::cos(M_PI * double(params_.filter_angle)));
  f.interpolation_jitter = params_.interpolation_jitter;
  f.denoise_history = params_.denoise_history;
  f.restir_candidates = uint32_t(params_.world_restir_candidates);
  f.restir_cap = params_.world_restir_cap;
  f.path_bounces = params_.cache_path_bounces;
  f.side_slots = sizes_.side_slots;
  executor.begin_frame(context, f);
  executor.clear_counters();

  std::map<std::string, double> buckets;
  buckets["direct"] = direct_ms;
  auto run = [&](uint32_t stage, uint32_t pass, uint64_t count) {
    double ms = executor.run(stage, pass, uint32_t(count));
    timer.add(std::string("gi10_") + kStageNames[stage], ms);
    buckets[bucket_of(stage)] += ms;
  };
  run(GI10_STAGE_GBUFFER, 0, sizes_.pixels());
  if (frame_ == 0) {
    // The yardstick D of cache cell sizes: the median view depth of what the camera sees at the
    // first frame (core/render/view_length.h), within 0.4-1.2x the diagonal of what it sees in the
    // shared interiors, but blind to a landscape seen through a window, which made that diagonal
    // 14x the room's.
    std::vector<glsl::Gi10Pixel> pixels;
    executor.read_pixels(pixels);
    std::vector<float> depths;
    for (const auto& p : pixels)
      if (p.depth > 0.0f) depths.push_back(p.depth);
    view_length_ = median_distance(std::move(depths));
    if (!(view_length_ > 0.0f)) view_length_ = std::max(context.scene.bounds.diagonal(), 1e-6f);
  }
  if (resolved_.capsaicin_cells) {
    f.hash_base_exp = -10;  // 2^-10 units, Capsaicin's 1 mm where a unit is a metre
    f.min_cell = 0.1f;
  } else {
    f.hash_base_exp = int(std::floor(std::log2(double(view_length_)))) - 16;
    f.min_cell = params_.min_cell_ratio * view_length_;
  }
  f.hash_base_exp = std::clamp(f.hash_base_exp, -100, 100);
  executor.begin_frame(context, f);

  run(GI10_STAGE_PURGE, 0, sizes_.hash_tiles);
  run(GI10_STAGE_REPROJECT, 0, sizes_.tiles());
  run(GI10_STAGE_SPAWN, 0, sizes_.spawns());
  run(GI10_STAGE_EMPTY_TILES, 0, sizes_.tiles());
  run(GI10_STAGE_LIST_COUNT, 0, sizes_.list_blocks());
  run(GI10_STAGE_LIST_SCAN, 0, 1);
  run(GI10_STAGE_LIST_COMPACT, 0, sizes_.list_blocks());
  run(GI10_STAGE_PATCH, 0, std::min(sizes_.spawns(), sizes_.tiles()));
  if (sizes_.side_slots > 0)
    for (uint32_t pass = 0; pass <= kGiSideListLength; ++pass) run(GI10_STAGE_SIDE_LOOKUP, pass, sizes_.side_slots);
  run(GI10_STAGE_SAMPLE, 0, sizes_.spawns());
  if (sizes_.side_slots > 0) run(GI10_STAGE_SIDE_ALLOCATE, 0, 1);
  run(GI10_STAGE_TRACE, 0, sizes_.spawns() * 64);
  run(GI10_STAGE_SHADE, 0, sizes_.spawns() * 64);
  if (params_.world_restir) run(GI10_STAGE_STORE_RESERVOIR, 0, sizes_.spawns() * 64);
  run(GI10_STAGE_UPDATE, 0, sizes_.hash_tiles);
  run(GI10_STAGE_RESOLVE, 0, sizes_.spawns() * 64);
  run(GI10_STAGE_BLEND, 0, sizes_.spawns());
  if (sizes_.side_slots > 0) {
    const uint64_t blocks = (sizes_.side_slots + kGiBlock - 1) / kGiBlock;
    run(GI10_STAGE_SIDE_REORDER, 0, blocks);
    run(GI10_STAGE_SIDE_REORDER, 1, 1);
    run(GI10_STAGE_SIDE_REORDER, 2, blocks);
  }
  for (uint32_t level = 1; level < sizes_.mask_levels; ++level) {
    glm::uvec2 size = gi10_mask_level_size(sizes_, level);
    run(GI10_STAGE_MASK_MIP, level, uint64_t(size.x) * size.y);
  }
  if (params_.probe_filter) {
    run(GI10_STAGE_COPY_PROBES, 0, sizes_.tiles() * 64);
    run(GI10_STAGE_FILTER, 0, sizes_.spawns() * 64);
    run(GI10_STAGE_FILTER, 1, sizes_.spawns() * 64);
  }
  run(GI10_STAGE_PROJECT, 0, sizes_.spawns());
  run(GI10_STAGE_INTERPOLATE, 0, sizes_.pixels());
  if (params_.irradiance_denoiser) {
    run(GI10_STAGE_DENOISE_REPROJECT, 0, sizes_.pixels());
    run(GI10_STAGE_BLUR_MASK, 0, sizes_.pixels());
    run(GI10_STAGE_FILTER_GI, 0, sizes_.pixels());
    run(GI10_STAGE_FILTER_GI, 1, sizes_.pixels());
  }

  // Compose: L = Le + direct (the direct pass) + albedo / pi x E_out, with the samples' albedo.
  auto start = std::chrono::steady_clock::now();
  std::vector<vec4> denoised, raw;
  executor.read_irradiance(denoised, raw);
  const std::vector<vec4>& e = params_.irradiance_denoiser ? denoised : raw;
  Image raw_image(context.width, context.height), e_image(context.width, context.height);
  Image hint_image(context.width, context.height);
  std::vector<vec4> feedback(sizes_.pixels());
  tbb::parallel_for(0, context.height, [&](int y) {
    for (int x = 0; x < context.width; ++x) {
      size_t i = size_t(y) * size_t(context.width) + size_t(x);
      auto clean = [](vec4 v) {
        vec3 c = glm::max(vec3(v.x, v.y, v.z), vec3(0.0f));
        return is_finite(c) ? c : vec3(0.0f);
      };
      vec3 irradiance = clean(e[i]);
      vec3 indirect = out.albedo.rgb(x, y) * irradiance * float(1.0 / M_PI);
      vec3 color = out.direct.rgb(x, y) + indirect;
      out.indirect.set_rgb(x, y, indirect);
      out.color.set_rgb(x, y, color);
      e_image.set_rgb(x, y, irradiance);
      raw_image.set_rgb(x, y, clean(raw[i]));
      hint_image.set_rgb(x, y, vec3(raw[i].w > 0.0f ? 1.0f : 0.0f));
      feedback[i] = vec4(color, 0.0f);
    }
  });
  executor.write_feedback(feedback);
  double compose_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  timer.add("gi10_compose", compose_ms);
  buckets["compose"] += compose_ms;
  run(GI10_STAGE_FEEDBACK, 0, sizes_.pixels());

  previous_view_ = f.view;
  ++frame_;
  if (warmup) return out;
  std::vector<uint32_t> c = executor.counters();
  double pixels = double(sizes_.pixels());
  nlohmann::json counters = {{"probes", c[GI10_COUNT_PROBES]},
                             {"patched_probes", c[GI10_COUNT_PATCHED]},
                             {"empty_tiles", c[GI10_COUNT_EMPTY]},
                             {"probe_rays", uint64_t(c[GI10_COUNT_PROBES]) * 64},
                             {"probe_hits", c[GI10_COUNT_HITS]},
                             {"insert_failed", c[GI10_COUNT_INSERT_FAILED]},
                             {"new_tiles", c[GI10_COUNT_NEW_TILES]},
                             {"live_tiles", c[GI10_COUNT_LIVE_TILES]},
                             {"evicted_tiles", c[GI10_COUNT_EVICTED]},
                             {"feedback_rays", c[GI10_COUNT_FEEDBACK]},
                             {"cache_shadow_rays", c[GI10_COUNT_SHADOW_RAYS]},
                             {"bypass_rays", c[GI10_COUNT_BYPASS]},
                             {"reservoirs_reused", c[GI10_COUNT_RESERVOIRS_REUSED]},
                             {"probes_without_history", c[GI10_COUNT_NO_HISTORY]},
                             {"side_evicted", c[GI10_COUNT_SIDE_EVICTED]},
                             {"side_allocated", c[GI10_COUNT_SIDE_ALLOCATED]},
                             {"side_used", c[GI10_COUNT_SIDE_USED]},
                             {"relaxed_pixels", c[GI10_COUNT_RELAXED]},
                             {"pixels_without_probe", c[GI10_COUNT_NO_PROBE]},
                             {"emissive_rays", c[GI10_COUNT_EMISSIVE]},
                             {"probe_rays_per_pixel", double(c[GI10_COUNT_PROBES]) * 64.0 / pixels},
                             {"cache_shadow_rays_per_pixel", double(c[GI10_COUNT_SHADOW_RAYS]) / pixels},
                             {"frames_rendered", frame_},
                             {"view_length", view_length_},
                             {"cell_base", std::ldexp(1.0, f.hash_base_exp)},
                             {"min_cell", f.min_cell}};
  out.method_counters = counters;
  out.method_counters["buckets_ms"] = buckets;
  out.counters.bounce_rays += uint64_t(c[GI10_COUNT_PROBES]) * 64;
  out.counters.shadow_rays += c[GI10_COUNT_SHADOW_RAYS];
  out.extra_layers = {{"gi10_irradiance", e_image}, {"gi10_irradiance_raw", raw_image}, {"gi10_probe_hint", hint_image}};
  return out;
}

Gi10Method::Gi10Method(const Gi10Params& params) : renderer_(params), cpu_(std::make_unique<Gi10Cpu>()) {}
Gi10Method::~Gi10Method() = default;

FrameOutput Gi10Method::render(const RenderContext& context, StageTimer& timer) {
  return renderer_.render(context, *cpu_, timer);
}

nlohmann::json Gi10Method::params() const { return params_to_json(renderer_.params()); }

MethodInfo gi10_method_info() {
  MethodInfo info = method_info<Gi10Params>(
      "gi10",
      "GI-1.0 (Boisse et al. 2022): screen probes at 1/4 ray per pixel over a world-space hash-grid radiance cache, "
      "reprojected, filtered and denoised over frames (warm-up frames first), plus sst's direct pass",
      [](const Gi10Params& p) -> std::unique_ptr<Method> { return std::make_unique<Gi10Method>(p); });
  return info;
}

}  // namespace sst
