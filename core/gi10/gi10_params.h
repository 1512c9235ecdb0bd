// The parameters of `gi10` (GI-1.0; docs/design/gi10.md, presets). Every constant of
// Capsaicin's implementation is a field with its default; the switches in which the presets
// differ read "auto" and take the preset's value (resolve_gi10).
#pragma once
#include <string>

#include "core/gi10/gi10_layout.h"
#include "core/util/params.h"

namespace sst {

struct Gi10Params {
  std::string preset = "fair";
  bool feedback = true;
  std::string probe_emission = "auto";
  std::string backup = "auto";
  std::string sh_weight = "auto";
  std::string blur_mask = "auto";
  std::string cell_base = "auto";
  int cache_warmup_frames = 64;
  float hash_cell_px = 32.0f;
  int cell_px_height = 1080;
  float min_cell_ratio = 0.003f;
  int hash_buckets_log2 = 12;
  int tiles_per_bucket_log2 = 4;
  int max_samples = 16;
  int tile_decay = 50;
  float reproject_normal = 0.95f;
  float feedback_normal = 0.5f;
  float feedback_depth = 0.05f;
  float filter_angle = 0.02f;
  float interpolation_jitter = 16.0f;
  float denoise_history = 8.0f;
  bool guiding = true;
  bool probe_filter = true;
  bool irradiance_denoiser = true;
  bool bypass = true;
  bool short_ray_bit = true;
  bool hysteresis = true;
  std::string texel_estimate = "fill";
  bool cache_lookup = true;
  std::string irradiance_basis = "sh";
  bool world_restir = false;
  int world_restir_candidates = 8;
  float world_restir_cap = 20.0f;
  std::string world_restir_combine = "unbiased";
  std::string cache_shading = "light";
  int cache_path_bounces = 8;
  std::string side_cache = "auto";

  template <class V>
  void visit(V&& v) {
    v("preset", preset,
      "fair: sst's direct pass for all direct light, probes see reflected light only, the corrected SH weight "
      "2 pi/64, the reached texels' mean as fill of empty ones, scene-relative cache cells; capsaicin: AMD Capsaicin v1.2's "
      "behaviour (emitters seen by probes return their emission, SH weight 1/8, its darker fill, 1 mm / 0.1 cell base, its blur mask)");
    v("feedback", feedback,
      "temporal radiance feedback: cache points visible last frame take last frame's image (light of every bounce) "
      "instead of a light sample (one bounce)");
    v("probe_emission", probe_emission, "auto|on|off: probe rays that hit an emitter return its emission (on "
      "double-counts direct light with sst's direct pass)");
    v("backup", backup, "auto|mean|spread: radiance of probe texels no ray reached: the mean of the reached "
      "texels (fair) or that mean spread over the empty ones, divided by their number (capsaicin)");
    v("sh_weight", sh_weight, "auto|solid_angle|capsaicin: SH projection weight per texel, 2 pi/64 (solid_angle) or 1/8 (capsaicin)");
    v("blur_mask", blur_mask, "auto|full|capsaicin: the denoiser's blur-mask dilation; capsaicin skips the centre "
      "row and column");
    v("cell_base", cell_base, "auto|scene|capsaicin: cache cells are 2^k times 2^(floor(log2 D)-16) with D the "
      "median view depth of what the camera sees at frame 0 and at least min_cell_ratio D (scene), or 2^-10 units and at "
      "least 0.1 units (capsaicin)");
    v("cache_warmup_frames", cache_warmup_frames,
      "frames rendered at the first view before frame 0 of a render or sequence (untimed, discarded): the caches "
      "fill over frames");
    v("hash_cell_px", hash_cell_px, "projected size of a cache cell in pixels at an image cell_px_height high "
      "(Capsaicin 32 at 1080)");
    v("cell_px_height", cell_px_height, "image height at which hash_cell_px holds; other heights scale it, so cache "
      "cells keep their world size across resolutions (0: hash_cell_px at every height, as Capsaicin)");
    v("min_cell_ratio", min_cell_ratio, "smallest cache cell as a fraction of D, the median view depth at frame 0 (cell_base scene)");
    v("hash_buckets_log2", hash_buckets_log2,
      "log2 of the cache's buckets (Capsaicin 12; a full bucket loses rays: counters.insert_failed)");
    v("tiles_per_bucket_log2", tiles_per_bucket_log2, "log2 of the hash tiles per bucket (linear-probing length)");
    v("max_samples", max_samples, "cache cells' sample-count cap: the average's window and the mip threshold");
    v("tile_decay", tile_decay, "frames without a touch after which a hash tile is freed");
    v("reproject_normal", reproject_normal, "cosine a pixel's normal must exceed to continue a previous probe");
    v("feedback_normal", feedback_normal, "cosine of the feedback's normal test against the previous G-buffer");
    v("feedback_depth", feedback_depth, "relative depth tolerance of the feedback's test");
    v("filter_angle", filter_angle, "probe filter's parallax threshold, in units of pi (cos(0.02 pi))");
    v("interpolation_jitter", interpolation_jitter, "pixels by which the probe search of a pixel is jittered");
    v("denoise_history", denoise_history, "the denoiser's history cap: lerp(4, this x min(n, 8), beta) x vignette");
    v("guiding", guiding, "probe rays guided by the reprojected radiance (paper 2.1.3); off: one ray per texel");
    v("probe_filter", probe_filter, "filter traced probes across their neighbours (paper Algorithm 5)");
    v("irradiance_denoiser", irradiance_denoiser, "GI-1.0's own temporal denoiser; off: the interpolated irradiance");
    v("bypass", bypass, "probe rays shorter than a cell keep their own light sample instead of the cell's");
    v("short_ray_bit", short_ray_bit, "the short-ray bit (hit closer than a hash tile) in the cache key");
    // The four below replace a biased mechanism of the paper by its exact form, for measuring
    // what each contributes to the bias (docs/design/gi10.md, "Where the bias comes from").
    v("hysteresis", hysteresis, "the paper's shadow-preserving hysteresis (Algorithm 3) blends a traced texel with its "
      "reconstruction; off: the new value alone (no temporal blend of probe radiance)");
    v("texel_estimate", texel_estimate, "fill|expected: a traced texel's radiance is the mean of the rays that landed "
      "in it, empty texels filled by `backup` (fill, the paper), or the sum of its rays over the number guiding expected "
      "there, which is unbiased and needs no fill (expected)");
    v("cache_lookup", cache_lookup, "probe rays read their cache cell's average (S13); off: every ray keeps its own "
      "light sample or feedback value (the cache still fills), the cache's exact form");
    v("irradiance_basis", irradiance_basis, "sh|texels: a pixel's irradiance from its probes' L2 SH (the paper) or "
      "from the cosine integrated over their 64 texels (no SH truncation)");
    v("cache_shading", cache_shading, "light|path: the radiance of a cache point the feedback image does not show (all "
      "of them without feedback): its direct light (one light sample or world_restir's reservoir: the paper) or a path "
      "traced from it with every bounce (the exact form, which the feedback approximates where it can; costs a path "
      "per such point)");
    v("cache_path_bounces", cache_path_bounces, "cache_shading path: the path's bounces counted from the pixel, as pt's "
      "max_bounces (8)");
    v("world_restir", world_restir, "world-space ReSTIR for the light at cache points (paper 2.3.1; off in Capsaicin's "
      "defaults): RIS over world_restir_candidates light samples, merged with the reservoir the previous frame left in the "
      "point's hash tile; off: one light sample");
    v("world_restir_candidates", world_restir_candidates, "world_restir: light samples per cache point (Capsaicin 8)");
    v("world_restir_cap", world_restir_cap, "world_restir: the previous reservoir's M is capped at this many times the "
      "new one's (Capsaicin 20)");
    v("side_cache", side_cache, "auto|on|off: the paper's LRU side cache of screen probes (2.1.8; fair off, capsaicin "
      "on): a probe that a new one replaces without feeding its reconstruction is kept in a slot, and new probes near it "
      "reconstruct from it, so probes on thin geometry keep their history; a slot per screen tile, the least recently "
      "used taken first");
    v("world_restir_combine", world_restir_combine, "world_restir: unbiased (the previous sample's weight checked with "
      "a shadow ray, as ReSTIR DI's restir_combine) or biased (without; Capsaicin merges without it)");
  }
};

// The flags and weights the preset and the "auto" fields resolve to; throws sst::Error naming a
// field whose value is not one of its choices.
struct Gi10Resolved {
  uint32_t flags = 0;
  float sh_weight = 0.0f;
  bool capsaicin_cells = false;
  bool side_cache = false;
};
Gi10Resolved resolve_gi10(const Gi10Params& p);
void validate(const Gi10Params& p);

}  // namespace sst
