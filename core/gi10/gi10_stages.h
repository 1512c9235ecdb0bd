// GI-1.0's stages (GI1.md §2 and §5, S1-S20 without the optional side cache and world-space
// ReSTIR), each as the work of one element (a pixel, a screen tile, a probe, a ray, a hash tile),
// written once for both backends: gi10_method.cpp runs them in oneTBB loops, gpu/shaders/gi10.comp
// dispatches them. Every sum is taken in a fixed order by one invocation, or in fixed point
// (gi_fixed_split), so both backends and every thread count give the same bits.
//
// Hooks, besides the scene's, lights' and rays' (core/pt/trace_path.h lists those):
//   GI_CTX_PARAM / GI_CTX   the buffers' context parameter and argument (empty in GLSL)
//   GF                      the frame's Gi10Frame
//   GI_PIXELS(i) ... GI_OUTPUT(i)     the buffers listed below, as lvalues
//   GI_ATOMIC_ADD(lvalue, v), GI_ATOMIC_CAS(lvalue, compare, v)   return the old value
//
// Buffer layout (element type, count): PIXELS Gi10Pixel 2 W H (this frame's and the previous, by
// frame parity); EMISSION vec4 W H (emission seen at the pixel centres); MASK uint 2 M (M: all
// mips of the tile grid); RADIANCE vec4 2 Nt 64 (rgb, hit distance); SH vec4 2 Nt 9; SPAWN uint
// gi_spawn_words (spawn list and the patch's lists); RAYS Gi10Ray Ns 64; HASH uint 2 T (checksums,
// then last-touch frames); VALUES vec4 T 85; ACCUM uint T 64 kGiAccumWords; DENOISE vec4 3 W H
// (irradiance + hint, history x2); AUX vec4 3 W H (colour delta and blur masks x2, filter
// scratch); FEEDBACK vec4 W H; COUNTERS uint GI10_COUNTERS; OUTPUT vec4 W H (E_out). No buffer
// exceeds lavapipe's 128 MiB at 1920 x 1080 with the default cache.
#ifndef SST_CORE_GI10_GI10_STAGES_H
#define SST_CORE_GI10_GI10_STAGES_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/gi10/gi10_layout.h"
#include "core/gi10/gi10_math.h"
#include "core/render/pinhole.h"
#include "core/render/reprojection.h"
#include "core/rng/hash_rng.h"

#ifdef __cplusplus
namespace sst {
using glsl::Gi10Frame;
using glsl::Gi10Pixel;
using glsl::Gi10Ray;
}  // namespace sst
#endif

SST_BEGIN

// ---- indexing -------------------------------------------------------------------------------------
SST_FUNC uint gi_parity(SST_IN(Gi10Frame) f) { return f.frame & 1u; }
SST_FUNC uint gi_pixels(SST_IN(Gi10Frame) f) { return f.width * f.height; }
SST_FUNC uint gi_tiles(SST_IN(Gi10Frame) f) { return f.tiles_x * f.tiles_y; }
SST_FUNC uint gi_spawns(SST_IN(Gi10Frame) f) { return f.spawn_x * f.spawn_y; }
SST_FUNC uint gi_hash_tiles(SST_IN(Gi10Frame) f) { return f.num_buckets * f.tiles_per_bucket; }
SST_FUNC uint gi_pack(uvec2 p) { return (p.x << 16u) | p.y; }
SST_FUNC uvec2 gi_unpack(uint v) { return uvec2(v >> 16u, v & 0xFFFFu); }
SST_FUNC uint gi_pixel_index(SST_IN(Gi10Frame) f, uvec2 p) { return p.y * f.width + p.x; }
SST_FUNC uint gi_tile_of(SST_IN(Gi10Frame) f, uvec2 p) { return (p.y / 8u) * f.tiles_x + p.x / 8u; }  // screen tile

// Mip `level` of the probe mask: its size and first element (within one of the two copies).
SST_FUNC uvec2 gi_mask_size(SST_IN(Gi10Frame) f, uint level) {
  uvec2 s = uvec2(f.tiles_x, f.tiles_y);
  for (uint i = 0u; i < level; ++i) s = uvec2(max((s.x + 1u) / 2u, 1u), max((s.y + 1u) / 2u, 1u));
  return s;
}

SST_FUNC uint gi_mask_offset(SST_IN(Gi10Frame) f, uint level) {
  uint offset = 0u;
  uvec2 s = uvec2(f.tiles_x, f.tiles_y);
  for (uint i = 0u; i < level; ++i) {
    offset += s.x * s.y;
    s = uvec2(max((s.x + 1u) / 2u, 1u), max((s.y + 1u) / 2u, 1u));
  }
  return offset;
}

SST_FUNC uint gi_mask_total(SST_IN(Gi10Frame) f) { return gi_mask_offset(f, f.mask_levels); }

SST_FUNC bool gi_is_miss(float distance) { return distance >= 0.5f * kGiMissDistance; }

// The screen-space cell size at a point: the distance to the eye times k (Alg. 6 of the paper).
SST_FUNC float gi_cell_size(vec3 eye, vec3 x, float k) { return length3(eye - x) * k; }

SST_FUNC vec4 gi_vec4(vec3 c, float a) { return vec4(c.x, c.y, c.z, a); }
SST_FUNC vec3 gi_rgb(vec4 v) { return vec3(v.x, v.y, v.z); }
SST_FUNC float gi_saturate(float x) { return clamp(x, 0.0f, 1.0f); }
SST_FUNC float gi_pow8(float x) {
  float x2 = x * x;
  float x4 = x2 * x2;
  return x4 * x4;
}
// 2^x for x <= 0 from + and * only (the drivers' exp differs by ulps between backends, and the
// denoiser's output feeds back into the next frames): 2^floor(x) from the exponent bits times a
// degree-6 Taylor polynomial of 2^f, f in [0, 1) (relative error < 1e-5).
SST_FUNC float gi_exp2_negative(float x) {
  if (!(x > -126.0f)) return 0.0f;
  float i = floor(x);
  SST_PRECISE float t = (x - i) * 0.69314718f;
  SST_PRECISE float p = 1.0f + t * (1.0f + t * (0.5f + t * (0.16666667f + t * (0.041666668f + t * (0.008333334f + t * 0.0013888889f)))));
  return p * uintBitsToFloat(uint(int(i) + 127) << 23u);
}

SST_FUNC vec3 gi_scrub(vec3 c) { return is_finite3(c) ? max3(c, vec3(0.0f)) : vec3(0.0f); }

// A random stream of GI-1.0: one per (stage, element) and frame.
SST_FUNC HashRng gi_rng(SST_IN(Gi10Frame) f, uint stage, uint element) {
  return hash_rng(f.seed, element, f.frame, 0x61100000u + stage);
}

// A unit vector in 32 bits (octahedral map, 16 bits per axis), the same bits on both backends.
SST_FUNC uint gi_oct_encode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  if (!(l1 > 0.0f)) return 0x7FFF7FFFu;
  float u = n.x / l1;
  float v = n.y / l1;
  if (n.z < 0.0f) {
    float fu = (1.0f - abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    float fv = (1.0f - abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
    u = fu;
    v = fv;
  }
  uint qu = uint(clamp(floor((u * 0.5f + 0.5f) * 65535.0f + 0.5f), 0.0f, 65535.0f));
  uint qv = uint(clamp(floor((v * 0.5f + 0.5f) * 65535.0f + 0.5f), 0.0f, 65535.0f));
  return (qu << 16u) | qv;
}

SST_FUNC vec3 gi_oct_decode(uint e) {
  float u = float(e >> 16u) * (2.0f / 65535.0f) - 1.0f;
  float v = float(e & 0xFFFFu) * (2.0f / 65535.0f) - 1.0f;
  float z = 1.0f - abs(u) - abs(v);
  if (z < 0.0f) {
    float fu = (1.0f - abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    float fv = (1.0f - abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
    u = fu;
    v = fv;
  }
  return normalize3(vec3(u, v, z));
}

SST_FUNC Gi10Pixel gi_pixel(GI_CTX_PARAM uint copy, uint index) { return GI_PIXELS(copy * gi_pixels(GF) + index); }
SST_FUNC bool gi_sky(SST_IN(Gi10Pixel) p) { return !(p.depth > 0.0f); }
SST_FUNC vec3 gi_ns(SST_IN(Gi10Pixel) p) { return gi_oct_decode(p.ns); }

// ---- G-buffer of pixel centres -------------------------------------------------------------------
SST_FUNC void gi_stage_gbuffer(SCENE_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index) {
  uint x = index % GF.width;
  uint y = index / GF.width;
  vec3 dir = camera_direction(GF.view, float(x) + 0.5f, float(y) + 0.5f);
  Gi10Pixel p;
  p.position = vec3(0.0f);
  p.depth = 0.0f;
  p.ng = vec3(0.0f);
  p.ns = 0u;
  vec3 emission = vec3(0.0f);
  BvhHit h = RAY_INTERSECT(GF.view.eye, dir);
  if (h.triangle < BVH_STACK_OVERFLOW) {
    Surface s = make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), dir);
    p.position = s.p;
    p.depth = max(dot3(s.p - GF.view.eye, GF.view.forward), 1e-30f);
    p.ng = s.ng;
    p.ns = gi_oct_encode(s.ns);
    emission = s.emission;
  }
  GI_PIXELS(gi_parity(GF) * gi_pixels(GF) + index) = p;
  GI_EMISSION(index) = gi_vec4(emission, 0.0f);
}

// ---- S1: free the hash tiles untouched for tile_decay frames ---------------------------------------
SST_FUNC void gi_stage_purge(GI_CTX_PARAM uint slot) {
  if (GI_HASH(slot) == 0u) return;
  uint age = GF.frame - GI_HASH(gi_hash_tiles(GF) + slot);
  if (age >= GF.tile_decay) {
    GI_HASH(slot) = 0u;
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_EVICTED), 1u);
  } else {
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_LIVE_TILES), 1u);
  }
}

// ---- probe texel accumulation (S2, S6, S14): one invocation owns the 64 sums -----------------------
struct GiTexelSums {
  vec4 sum[64];  // radiance, hit distance
  float count[64];
};

SST_FUNC void gi_sums_clear(SST_INOUT(GiTexelSums) a) {
  for (uint c = 0u; c < 64u; ++c) {
    a.sum[c] = vec4(0.0f);
    a.count[c] = 0.0f;
  }
}

// Adds the texel of another probe (at xq, frame fq) seen from probe x, n (frame fx): its radiance
// arrives from the point it hit (parallax), or, for a miss, from its direction.
SST_FUNC void gi_sums_add_reprojected(SST_INOUT(GiTexelSums) a, vec3 x, vec3 n, SST_IN(GiFrame) fx, vec3 xq,
                                      SST_IN(GiFrame) fq, uint c, vec4 value, bool strict_hemisphere) {
  vec3 wq = gi_texel_direction(fq, c);
  vec3 w;
  float d;
  if (gi_is_miss(value.w)) {
    w = wq;
    d = kGiMissDistance;
  } else {
    SST_PRECISE vec3 h = xq + wq * value.w;
    vec3 hx = h - x;
    d = length3(hx);
    if (!(d > 0.0f)) return;
    w = hx / d;
  }
  float cos_n = dot3(n, w);
  if (strict_hemisphere ? !(cos_n > 0.0f) : !(cos_n >= 0.0f)) return;
  uint k = gi_texel_of(fx, w);
  a.sum[k] += vec4(value.x, value.y, value.z, d);
  a.count[k] += 1.0f;
}

// The radiance given to texels that received nothing: the mean of the texels rays reached, or, as
// Capsaicin computes it, that mean spread over the empty texels (divided by their number; GI1.md
// B4). Guiding sends no ray to the texels it predicts dark, so the mean brightens them and the
// spread darkens them: measured in configs/gi10-static-one-bounce.json.
SST_FUNC vec3 gi_backup(SST_IN(GiTexelSums) a, bool mean) {
  vec3 sum = vec3(0.0f);
  vec3 texel_means = vec3(0.0f);
  float populated = 0.0f;
  for (uint c = 0u; c < 64u; ++c) {
    sum += gi_rgb(a.sum[c]);
    if (a.count[c] > 0.0f) {
      texel_means += gi_rgb(a.sum[c]) / a.count[c];
      populated += 1.0f;
    }
  }
  if (!mean) return sum / max(populated, 1.0f) / max(64.0f - populated, 1.0f);
  return populated > 0.0f ? texel_means / populated : vec3(0.0f);
}

SST_FUNC vec4 gi_sums_texel(SST_IN(GiTexelSums) a, uint c, vec3 backup) {
  if (a.count[c] > 0.0f) return a.sum[c] / a.count[c];
  return gi_vec4(backup, kGiMissDistance);
}

// ---- S2: reproject the previous frame's probes, one screen tile at a time --------------------------
SST_FUNC void gi_stage_reproject(GI_CTX_PARAM uint tile) {
  uint cur = gi_parity(GF);
  uint prev = cur ^ 1u;
  uint tx = tile % GF.tiles_x;
  uint ty = tile / GF.tiles_x;
  uint mask_base = cur * gi_mask_total(GF);
  uint prev_mask_base = prev * gi_mask_total(GF);
  // The vote: the pixel of this tile closest (in cell sizes) to a previous probe it can continue.
  float best = 3.0e38f;
  uint best_lane = 64u;
  uint best_prev = kGiNoProbe;
  if (GF.has_history != 0u) {
    for (uint lane = 0u; lane < 64u; ++lane) {
      uvec2 p = uvec2(tx * 8u + (lane & 7u), ty * 8u + (lane >> 3u));
      if (p.x >= GF.width || p.y >= GF.height) continue;
      Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, p));
      if (gi_sky(px)) continue;
      vec2 q;
      float distance;
      if (!project_to_pixel(GF.previous_view, px.position, q, distance)) continue;
      if (!(q.x >= 0.0f && q.y >= 0.0f && q.x < float(GF.width) && q.y < float(GF.height))) continue;
      uint qt = (uint(q.y) / 8u) * GF.tiles_x + uint(q.x) / 8u;
      uint packed = GI_MASK(prev_mask_base + qt);
      if (packed == kGiNoProbe) continue;
      Gi10Pixel pp = gi_pixel(GI_CTX prev, gi_pixel_index(GF, gi_unpack(packed)));
      if (gi_sky(pp)) continue;
      float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
      if (!(abs(dot3(pp.position - px.position, px.ng)) < cs) || !(dot3(px.ng, pp.ng) > GF.reproject_normal)) continue;
      float score = length3(pp.position - px.position) / cs;
      if (score < best) {
        best = score;
        best_lane = lane;
        best_prev = packed;
      }
    }
  }
  uint radiance_base = cur * gi_tiles(GF) * 64u + tile * 64u;
  if (best_lane == 64u) {
    GI_MASK(mask_base + tile) = kGiNoProbe;  // a disocclusion: the spawn stage may patch it
    return;
  }
  uvec2 seed = uvec2(tx * 8u + (best_lane & 7u), ty * 8u + (best_lane >> 3u));
  Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed));
  uvec2 prev_seed = gi_unpack(best_prev);
  Gi10Pixel pp = gi_pixel(GI_CTX prev, gi_pixel_index(GF, prev_seed));
  GiFrame fx = gi_frame(px.ng);
  GiFrame fp = gi_frame(pp.ng);
  uint prev_tile = gi_tile_of(GF, prev_seed);
  GiTexelSums a;
  gi_sums_clear(a);
  for (uint c = 0u; c < 64u; ++c)
    gi_sums_add_reprojected(a, px.position, px.ng, fx, pp.position, fp, c,
                            GI_RADIANCE(prev * gi_tiles(GF) * 64u + prev_tile * 64u + c), true);
  vec3 backup = gi_backup(a, (GF.flags & GI10_BACKUP_MEAN) != 0u);
  for (uint c = 0u; c < 64u; ++c) GI_RADIANCE(radiance_base + c) = gi_sums_texel(a, c, backup);
  // The SH move with the probe unchanged (no parallax): the paper's choice.
  for (uint k = 0u; k < 9u; ++k) GI_SH(cur * gi_tiles(GF) * 9u + tile * 9u + k) = GI_SH(prev * gi_tiles(GF) * 9u + prev_tile * 9u + k);
  GI_MASK(mask_base + tile) = gi_pack(seed);
}

// ---- S4 + S5: spawn probes and move rays from tiles that have a probe to disoccluded ones ----------
// Capsaicin appends both lists atomically and pairs them with random exchanges (a race). Here the
// lists are compacted in tile order (a block scan, so no invocation loops over the whole grid:
// lavapipe stops any invocation after 65535 loop iterations) and paired by a frame-keyed affine
// permutation, so the result is the same on every backend and thread count.
// SPAWN layout: [0, Ns) the spawn list (packed seed or kGiNoProbe); [Ns, 2Ns) override flags;
// [2Ns, 3Ns) the override list; [3Ns, 3Ns + Nt) empty-tile flags; then the empty list (Nt); then
// the blocks' counts (override blocks, then empty blocks); then the two list lengths.

SST_FUNC uint gi_override_blocks(SST_IN(Gi10Frame) f) { return (gi_spawns(f) + kGiBlock - 1u) / kGiBlock; }
SST_FUNC uint gi_empty_blocks(SST_IN(Gi10Frame) f) { return (gi_tiles(f) + kGiBlock - 1u) / kGiBlock; }
SST_FUNC uint gi_spawn_block_base(SST_IN(Gi10Frame) f) { return 3u * gi_spawns(f) + 2u * gi_tiles(f); }
SST_FUNC uint gi_spawn_words(SST_IN(Gi10Frame) f) {
  return gi_spawn_block_base(f) + gi_override_blocks(f) + gi_empty_blocks(f) + 2u;
}

SST_FUNC void gi_stage_spawn(GI_CTX_PARAM uint j) {
  uint cur = gi_parity(GF);
  uint ns = gi_spawns(GF);
  uvec2 seed = min(uvec2((j % GF.spawn_x) * 16u, (j / GF.spawn_x) * 16u) + GF.jitter16, uvec2(GF.width - 1u, GF.height - 1u));
  bool sky = gi_sky(gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed)));
  GI_SPAWN(j) = sky ? kGiNoProbe : gi_pack(seed);
  uint tile_mask = GI_MASK(cur * gi_mask_total(GF) + gi_tile_of(GF, seed));
  GI_SPAWN(ns + j) = (!sky && tile_mask != kGiNoProbe) ? 1u : 0u;  // an override: its tile has a probe
  if (!sky) GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_PROBES), 1u);
}

// A tile is empty when reprojection found no probe for it, this frame's spawn does not land in it
// and its first pixel is a surface.
SST_FUNC void gi_stage_empty_tiles(GI_CTX_PARAM uint t) {
  uint cur = gi_parity(GF);
  uint ns = gi_spawns(GF);
  uvec2 tp = uvec2(t % GF.tiles_x, t / GF.tiles_x);
  bool empty = GI_MASK(cur * gi_mask_total(GF) + t) == kGiNoProbe;
  uint spawned = GI_SPAWN((tp.y / 2u) * GF.spawn_x + tp.x / 2u);
  if (spawned != kGiNoProbe) {
    uvec2 s = gi_unpack(spawned);
    if (s.x / 8u == tp.x && s.y / 8u == tp.y) empty = false;
  }
  if (empty && gi_sky(gi_pixel(GI_CTX cur, gi_pixel_index(GF, tp * 8u)))) empty = false;
  GI_SPAWN(3u * ns + t) = empty ? 1u : 0u;
}

// Block b of the override flags (b < override blocks) or of the empty flags: its count.
SST_FUNC void gi_stage_list_count(GI_CTX_PARAM uint b) {
  uint ns = gi_spawns(GF);
  uint nbo = gi_override_blocks(GF);
  bool overrides = b < nbo;
  uint first = overrides ? ns : 3u * ns;
  uint n = overrides ? ns : gi_tiles(GF);
  uint block = overrides ? b : b - nbo;
  uint count = 0u;
  for (uint i = block * kGiBlock; i < min((block + 1u) * kGiBlock, n); ++i) count += GI_SPAWN(first + i);
  GI_SPAWN(gi_spawn_block_base(GF) + b) = count;
}

// One invocation: the blocks' counts become their first list positions; the list lengths follow.
SST_FUNC void gi_stage_list_scan(GI_CTX_PARAM uint index) {
  if (index != 0u) return;
  uint base = gi_spawn_block_base(GF);
  uint nbo = gi_override_blocks(GF);
  uint nbe = gi_empty_blocks(GF);
  uint sum = 0u;
  for (uint b = 0u; b < nbo; ++b) {
    uint c = GI_SPAWN(base + b);
    GI_SPAWN(base + b) = sum;
    sum += c;
  }
  GI_SPAWN(base + nbo + nbe) = sum;
  sum = 0u;
  for (uint b = 0u; b < nbe; ++b) {
    uint c = GI_SPAWN(base + nbo + b);
    GI_SPAWN(base + nbo + b) = sum;
    sum += c;
  }
  GI_SPAWN(base + nbo + nbe + 1u) = sum;
  GI_COUNTERS(GI10_COUNT_EMPTY) = sum;
}

SST_FUNC void gi_stage_list_compact(GI_CTX_PARAM uint b) {
  uint ns = gi_spawns(GF);
  uint nbo = gi_override_blocks(GF);
  bool overrides = b < nbo;
  uint flags = overrides ? ns : 3u * ns;
  uint list = overrides ? 2u * ns : 3u * ns + gi_tiles(GF);
  uint n = overrides ? ns : gi_tiles(GF);
  uint block = overrides ? b : b - nbo;
  uint at = GI_SPAWN(gi_spawn_block_base(GF) + b);
  for (uint i = block * kGiBlock; i < min((block + 1u) * kGiBlock, n); ++i)
    if (GI_SPAWN(flags + i) != 0u) {
      GI_SPAWN(list + at) = i;
      ++at;
    }
}

// (a k) mod n for a, k < n < 2^20 without 64-bit integers (GLSL has none by default).
SST_FUNC uint gi_mul_mod(uint a, uint k, uint n) {
  uint high = (a * (k >> 8u)) % n;
  return (high * 256u + a * (k & 255u)) % n;
}

SST_FUNC uint gi_gcd(uint a, uint b) {
  while (b != 0u) {
    uint t = a % b;
    a = b;
    b = t;
  }
  return a;
}

// Pair k of min(#empty, #override): the shorter list is taken in order, the longer one through
// k -> (a k + c) mod n with a coprime to n, both drawn from the frame's random numbers.
SST_FUNC void gi_stage_patch(GI_CTX_PARAM uint k) {
  uint ns = gi_spawns(GF);
  uint nlen = gi_spawn_block_base(GF) + gi_override_blocks(GF) + gi_empty_blocks(GF);
  uint no = GI_SPAWN(nlen);
  uint ne = GI_SPAWN(nlen + 1u);
  if (k >= min(no, ne)) return;
  uint n = max(no, ne);
  HashRng rng = gi_rng(GF, GI10_STAGE_PATCH, 0u);
  uint a = 1u + hash_rng_next_bits(rng) % n;
  uint c = hash_rng_next_bits(rng) % n;
  for (uint i = 0u; i < 32u && gi_gcd(a, n) != 1u; ++i) a = a % n + 1u;
  if (gi_gcd(a, n) != 1u) a = 1u;
  uint m = (gi_mul_mod(a, k, n) + c) % n;
  uint e = ne <= no ? k : m;
  uint o = ne <= no ? m : k;
  uint t = GI_SPAWN(3u * ns + gi_tiles(GF) + e);
  uvec2 tp = uvec2(t % GF.tiles_x, t / GF.tiles_x);
  uvec2 seed = min(tp * 8u + GF.jitter8, uvec2(GF.width - 1u, GF.height - 1u));
  if (gi_sky(gi_pixel(GI_CTX gi_parity(GF), gi_pixel_index(GF, seed)))) return;
  GI_SPAWN(GI_SPAWN(2u * ns + o)) = gi_pack(seed);
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_PATCHED), 1u);
}

// ---- S6: reconstruct a new probe from its reprojected neighbours and choose its ray directions ----
SST_FUNC void gi_stage_sample(GI_CTX_PARAM uint j) {
  uint cur = gi_parity(GF);
  uint packed = GI_SPAWN(j);
  if (packed == kGiNoProbe) {
    for (uint c = 0u; c < 64u; ++c) GI_RAYS(j * 64u + c).flags = 0u;
    return;
  }
  uvec2 seed = gi_unpack(packed);
  Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed));
  GiFrame fx = gi_frame(px.ng);
  float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
  int tx = int(seed.x / 8u);
  int ty = int(seed.y / 8u);
  uint mask_base = cur * gi_mask_total(GF);
  GiTexelSums a;
  gi_sums_clear(a);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      int qx = tx + dx;
      int qy = ty + dy;
      if (qx < 0 || qy < 0 || qx >= int(GF.tiles_x) || qy >= int(GF.tiles_y)) continue;
      uint qt = uint(qy) * GF.tiles_x + uint(qx);
      uint q = GI_MASK(mask_base + qt);
      if (q == kGiNoProbe) continue;
      Gi10Pixel pq = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(q)));
      if (!(abs(dot3(pq.position - px.position, px.ng)) <= cs)) continue;
      GiFrame fq = gi_frame(pq.ng);
      for (uint c = 0u; c < 64u; ++c)
        gi_sums_add_reprojected(a, px.position, px.ng, fx, pq.position, fq, c,
                                GI_RADIANCE(cur * gi_tiles(GF) * 64u + qt * 64u + c), false);
    }
  }
  // The guiding distribution: reconstructed luminance times the cosine at each texel's centre.
  float cdf[65];
  cdf[0] = 0.0f;
  for (uint c = 0u; c < 64u; ++c) {
    float w = 0.0f;
    if (a.count[c] > 0.0f) w = max(luminance(gi_rgb(a.sum[c])) / a.count[c], 0.0f) * gi_texel_local_direction(c, vec2(0.5f, 0.5f)).z;
    cdf[c + 1u] = cdf[c] + w;
  }
  float total = cdf[64];
  for (uint c = 0u; c < 64u; ++c) {
    HashRng rng = gi_rng(GF, GI10_STAGE_SAMPLE, j * 64u + c);
    float u = hash_rng_next(rng);
    // A lane whose own texel had history draws from the distribution; one without explores its
    // own texel (with no weight anywhere, every lane explores its own).
    uint texel = c;
    if ((GF.flags & GI10_GUIDING) != 0u && a.count[c] > 0.0f && total > 0.0f) {
      float target = u * total;
      texel = 0u;
      for (uint k = 1u; k < 64u; ++k)
        if (cdf[k] <= target) texel = k;
      while (texel > 0u && !(cdf[texel + 1u] > cdf[texel])) --texel;  // never a zero-weight texel
    }
    // One statement per draw: C++ leaves the order of a constructor's arguments open.
    float u1 = hash_rng_next(rng);
    float u2 = hash_rng_next(rng);
    vec2 uv = vec2(u1, u2);
    Gi10Ray r;
    r.direction = normalize3(gi_to_world(fx, gi_texel_local_direction(texel, uv)));
    r.recon_distance = a.count[c] > 0.0f ? a.sum[c].w / a.count[c] : -1.0f;
    r.recon = a.count[c] > 0.0f ? gi_rgb(a.sum[c]) / a.count[c] : vec3(0.0f);
    r.t = kGiMissDistance;
    r.x2 = vec3(0.0f);
    r.cell = 0u;
    r.n2 = vec3(0.0f);
    r.flags = GI10_RAY_ACTIVE;
    r.ns2 = vec3(0.0f);
    r.texel = texel;
    r.albedo2 = vec3(0.0f);
    r.cell_size = 0.0f;
    r.radiance = vec3(0.0f);
    r.pad1 = 0.0f;
    GI_RAYS(j * 64u + c) = r;
  }
}

// ---- S7: trace a probe ray and find (or make) its cache cell ----------------------------------------
// Linear probing that never duplicates a key: the whole bucket is searched before a free slot is
// taken (Capsaicin takes the first free slot, which after an eviction duplicates tiles, B6).
SST_FUNC uint gi_hash_insert(GI_CTX_PARAM SST_IN(GiCellKey) key, SST_OUT(bool) inserted) {
  inserted = false;
  uint bucket = gi_key_bucket(key, GF.num_buckets);
  uint checksum = gi_key_checksum(key);
  uint first = bucket * GF.tiles_per_bucket;
  for (uint i = 0u; i < GF.tiles_per_bucket; ++i)
    if (GI_HASH(first + i) == checksum) return first + i;
  for (uint i = 0u; i < GF.tiles_per_bucket; ++i) {
    uint previous = GI_ATOMIC_CAS(GI_HASH(first + i), 0u, checksum);
    if (previous == 0u) {
      inserted = true;
      return first + i;
    }
    if (previous == checksum) return first + i;
  }
  return kGiNoProbe;
}

SST_FUNC void gi_stage_trace(SCENE_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index) {
  Gi10Ray r = GI_RAYS(index);
  if ((r.flags & GI10_RAY_ACTIVE) == 0u) return;
  uint cur = gi_parity(GF);
  Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(GI_SPAWN(index / 64u))));
  vec3 origin = offset_ray_origin(GF.scene_epsilon, px.position, px.ng);
  BvhHit h = RAY_INTERSECT(origin, r.direction);
  if (h.triangle >= BVH_STACK_OVERFLOW) {
    GI_RAYS(index) = r;  // a miss: nothing enters the probe from the sky (sst's scenes have none)
    return;
  }
  Surface s = make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), r.direction);
  r.flags |= GI10_RAY_HIT;
  r.t = h.t;
  r.x2 = s.p;
  r.n2 = s.ng;
  r.ns2 = s.ns;
  r.albedo2 = s.base_color;
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_HITS), 1u);
  if ((GF.flags & GI10_PROBE_EMISSION) != 0u && max_component(s.emission) > 0.0f) {
    r.flags |= GI10_RAY_EMISSIVE;
    r.radiance = s.emission;
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_EMISSIVE), 1u);
    GI_RAYS(index) = r;
    return;
  }
  GiCellAddress a = gi_cell_address(GF.view.eye, s.p, r.direction, h.t, GF.k_hash, GF.min_cell, GF.hash_base_exp,
                                    (GF.flags & GI10_SHORT_RAY_BIT) != 0u);
  bool inserted;
  uint slot = gi_hash_insert(GI_CTX a.key, inserted);
  if (slot == kGiNoProbe) {
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_INSERT_FAILED), 1u);
    GI_RAYS(index) = r;
    return;
  }
  GI_HASH(gi_hash_tiles(GF) + slot) = GF.frame;
  if (inserted) {
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_NEW_TILES), 1u);
    for (uint c = 0u; c < 64u; ++c) GI_VALUES(slot * kGiCellsPerTile + c) = vec4(0.0f);
  }
  r.flags |= GI10_RAY_CELL;
  r.cell = gi_cell_index(slot, a.offset, 0u);
  r.cell_size = a.cell_size;
  GI_RAYS(index) = r;
}

// ---- S9 + S11: the radiance leaving a cache point toward the probe: the previous frame's image
// where the point was on screen (temporal feedback), else one light sample with one shadow ray ----
SST_FUNC void gi_accumulate(GI_CTX_PARAM uint cell, vec3 v) {
  uint slot = cell / kGiCellsPerTile;
  uint base = (slot * 64u + (cell - slot * kGiCellsPerTile)) * kGiAccumWords;
  for (uint ch = 0u; ch < 3u; ++ch) {
    uvec2 q = gi_fixed_split(ch == 0u ? v.x : (ch == 1u ? v.y : v.z));
    uint old = GI_ATOMIC_ADD(GI_ACCUM(base + 2u * ch), q.x);
    uint carry = old + q.x < old ? 1u : 0u;
    if (q.y + carry != 0u) GI_ATOMIC_ADD(GI_ACCUM(base + 2u * ch + 1u), q.y + carry);
  }
  GI_ATOMIC_ADD(GI_ACCUM(base + 6u), 1u);
}

SST_FUNC bool gi_feedback(GI_CTX_PARAM SST_IN(Gi10Ray) r, SST_OUT(vec3) value) {
  value = vec3(0.0f);
  if ((GF.flags & GI10_FEEDBACK) == 0u || GF.has_history == 0u) return false;
  vec2 q;
  float distance;
  // On screen now, and where the previous camera saw it.
  if (!project_to_pixel(GF.view, r.x2, q, distance)) return false;
  if (!(q.x >= 0.0f && q.y >= 0.0f && q.x < float(GF.width) && q.y < float(GF.height))) return false;
  if (!project_to_pixel(GF.previous_view, r.x2, q, distance)) return false;
  if (!(q.x >= 0.0f && q.y >= 0.0f && q.x < float(GF.width) && q.y < float(GF.height))) return false;
  uint i = gi_pixel_index(GF, uvec2(uint(q.x), uint(q.y)));
  Gi10Pixel pp = gi_pixel(GI_CTX gi_parity(GF) ^ 1u, i);
  if (gi_sky(pp)) return false;
  float z = dot3(r.x2 - GF.previous_view.eye, GF.previous_view.forward);
  if (!(dot3(pp.ng, r.n2) > GF.feedback_normal) || !(abs(pp.depth - z) < GF.feedback_depth * z)) return false;
  value = gi_scrub(gi_rgb(GI_FEEDBACK(i)));
  return true;
}

SST_FUNC void gi_stage_shade(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index) {
  Gi10Ray r = GI_RAYS(index);
  if ((r.flags & GI10_RAY_CELL) == 0u) return;
  vec3 fb;
  if (gi_feedback(GI_CTX r, fb)) {
    r.flags |= GI10_RAY_FEEDBACK;
    r.radiance += fb;
    gi_accumulate(GI_CTX r.cell, fb);
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_FEEDBACK), 1u);
    GI_RAYS(index) = r;
    return;
  }
  // sst's direct-light estimator at x2 (the lights picked as by every method's direct pass): a
  // Lambertian reflection toward the probe, unbiased, with no MIS (no BRDF sample to weigh).
  HashRng rng = gi_rng(GF, GI10_STAGE_SHADE, index);
  float u1 = hash_rng_next(rng);
  float u2 = hash_rng_next(rng);
  vec2 u = vec2(u1, u2);
  LightSample ls;
  if (!light_sample(SCENE_CTX LIGHT_CTX r.x2, r.ns2, u, ls)) {
    GI_RAYS(index) = r;
    return;
  }
  vec3 lo = vec3(0.0f);
  float cos_s = dot3(ls.wi, r.ns2);
  if (dot3(ls.wi, r.n2) > 0.0f && cos_s > 0.0f && ls.pdf > 0.0f && max_component(ls.li) > 0.0f) {
    vec3 origin;
    vec3 dir;
    float tmax;
    if (isinf(ls.distance)) {
      origin = offset_ray_origin(GF.scene_epsilon, r.x2, r.n2);
      dir = ls.wi;
      tmax = kInf;
    } else {
      shadow_ray_segment(GF.scene_epsilon, r.x2, r.n2, ls.offset, ls.point, ls.normal, origin, dir, tmax);
    }
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_SHADOW_RAYS), 1u);
    if (!RAY_OCCLUDED(origin, dir, tmax)) {
      SST_PRECISE vec3 v = r.albedo2 * (cos_s / (kPi * ls.pdf)) * ls.li;
      lo = gi_scrub(v);
    }
  }
  r.flags |= GI10_RAY_SHADOW;
  gi_accumulate(GI_CTX r.cell, lo);
  // A hit closer than a cell would read light from the probe's own surface neighbourhood through
  // the cell: it keeps its own sample instead (the cell is fed all the same).
  Gi10Pixel px = gi_pixel(GI_CTX gi_parity(GF), gi_pixel_index(GF, gi_unpack(GI_SPAWN(index / 64u))));
  if ((GF.flags & GI10_BYPASS) != 0u && length3(r.x2 - px.position) < r.cell_size) {
    r.flags |= GI10_RAY_BYPASS;
    r.radiance += lo;
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_BYPASS), 1u);
  }
  GI_RAYS(index) = r;
}

// ---- S12: fold this frame's samples into the touched tiles' cells, then their mips ----------------
SST_FUNC void gi_stage_update(GI_CTX_PARAM uint slot) {
  if (GI_HASH(slot) == 0u || GI_HASH(gi_hash_tiles(GF) + slot) != GF.frame) return;
  uint values = slot * kGiCellsPerTile;
  for (uint c = 0u; c < 64u; ++c) {
    uint a = (slot * 64u + c) * kGiAccumWords;
    vec3 sum = vec3(gi_fixed_value(GI_ACCUM(a), GI_ACCUM(a + 1u)), gi_fixed_value(GI_ACCUM(a + 2u), GI_ACCUM(a + 3u)),
                    gi_fixed_value(GI_ACCUM(a + 4u), GI_ACCUM(a + 5u)));
    float k = float(GI_ACCUM(a + 6u));
    GI_VALUES(values + c) = gi_cell_update(GI_VALUES(values + c), sum, k, GF.max_samples);
    for (uint w = 0u; w < kGiAccumWords; ++w) GI_ACCUM(a + w) = 0u;
  }
  // Mip m's cell is the sum (of mean x count and of count) of its four children at mip m - 1.
  for (uint m = 1u; m < 4u; ++m) {
    uint side = 8u >> m;
    for (uint oy = 0u; oy < side; ++oy) {
      for (uint ox = 0u; ox < side; ++ox) {
        vec4 s = vec4(0.0f);
        for (uint k = 0u; k < 4u; ++k)
          s += GI_VALUES(gi_cell_index(slot, uvec2((2u * ox + (k & 1u)) << (m - 1u), (2u * oy + (k >> 1u)) << (m - 1u)), m - 1u));
        GI_VALUES(gi_cell_index(slot, uvec2(ox << m, oy << m), m)) = s;
      }
    }
  }
}

// ---- S13: read the cache back into the probe rays: the finest mip with a full count ---------------
SST_FUNC void gi_stage_resolve(GI_CTX_PARAM uint index) {
  Gi10Ray r = GI_RAYS(index);
  if ((r.flags & GI10_RAY_SHADOW) == 0u || (r.flags & GI10_RAY_BYPASS) != 0u) return;
  uint slot = r.cell / kGiCellsPerTile;
  uint local = r.cell - slot * kGiCellsPerTile;
  uvec2 offset = uvec2(local & 7u, local >> 3u);
  vec4 v = GI_VALUES(r.cell);
  for (uint m = 1u; m < 4u && v.w < GF.max_samples; ++m) v = GI_VALUES(gi_cell_index(slot, offset, m));
  r.radiance += gi_rgb(v) / max(v.w, 1.0f);
  GI_RAYS(index) = r;
}

// ---- S14: a traced probe's texels: the mean of its rays, blended with its reconstruction through
// the shadow-preserving hysteresis (paper Algorithm 3) --------------------------------------------
SST_FUNC void gi_stage_blend(GI_CTX_PARAM uint j) {
  uint packed = GI_SPAWN(j);
  if (packed == kGiNoProbe) return;
  uint cur = gi_parity(GF);
  uvec2 seed = gi_unpack(packed);
  uint tile = gi_tile_of(GF, seed);
  GiTexelSums a;
  gi_sums_clear(a);
  for (uint c = 0u; c < 64u; ++c) {
    Gi10Ray r = GI_RAYS(j * 64u + c);
    vec3 l = gi_scrub(r.radiance);
    a.sum[r.texel] += vec4(l.x, l.y, l.z, r.t);
    a.count[r.texel] += 1.0f;
  }
  vec3 backup = gi_backup(a, (GF.flags & GI10_BACKUP_MEAN) != 0u);
  for (uint c = 0u; c < 64u; ++c) {
    vec4 value = gi_sums_texel(a, c, backup);
    Gi10Ray r = GI_RAYS(j * 64u + c);
    if (r.recon_distance >= 0.0f) {
      vec4 history = gi_vec4(r.recon, r.recon_distance);
      float alpha = gi_hysteresis(luminance(gi_rgb(value)), luminance(r.recon));
      value = value + (history - value) * alpha;
    }
    GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c) = value;
  }
  GI_MASK(cur * gi_mask_total(GF) + tile) = packed;
}

// ---- S16: the probe mask's mips: the first valid child of four, so a coarse entry names a probe ---
SST_FUNC void gi_stage_mask_mip(GI_CTX_PARAM uint level, uint index) {
  uint base = gi_parity(GF) * gi_mask_total(GF);
  uvec2 size = gi_mask_size(GF, level);
  uvec2 child_size = gi_mask_size(GF, level - 1u);
  uint child_base = base + gi_mask_offset(GF, level - 1u);
  uvec2 p = uvec2(index % size.x, index / size.x);
  uint v = kGiNoProbe;
  for (uint k = 0u; k < 4u && v == kGiNoProbe; ++k) {
    uvec2 c = uvec2(2u * p.x + (k & 1u), 2u * p.y + (k >> 1u));
    if (c.x < child_size.x && c.y < child_size.y) v = GI_MASK(child_base + c.y * child_size.x + c.x);
  }
  GI_MASK(base + gi_mask_offset(GF, level) + index) = v;
}

// A probe near `pixel`: the mask at its tile moved by `offset` tiles of mip 0, else mips up (where
// the offset reaches farther); kGiNoProbe when the search leaves the grid.
SST_FUNC uint gi_find_probe(GI_CTX_PARAM uvec2 pixel, ivec2 offset) {
  uint base = gi_parity(GF) * gi_mask_total(GF);
  ivec2 pos = ivec2(int(min(pixel.x / 8u, GF.tiles_x - 1u)), int(min(pixel.y / 8u, GF.tiles_y - 1u)));
  for (uint level = 0u; level < GF.mask_levels; ++level) {
    uvec2 size = gi_mask_size(GF, level);
    ivec2 loc = pos + offset;
    if (loc.x < 0 || loc.y < 0 || loc.x >= int(size.x) || loc.y >= int(size.y)) return kGiNoProbe;
    uint v = GI_MASK(base + gi_mask_offset(GF, level) + uint(loc.y) * size.x + uint(loc.x));
    if (v != kGiNoProbe) return v;
    pos = ivec2(pos.x / 2, pos.y / 2);
  }
  return kGiNoProbe;
}

// ---- S17: filter the traced probes' texels across neighbouring probes (paper Algorithm 5) ---------
// `source` and `target` are the two radiance copies (0 or 1); pass 0 filters along x, pass 1 along y.
SST_FUNC void gi_stage_filter(GI_CTX_PARAM uint pass, uint source, uint target, uint index) {
  uint j = index / 64u;
  uint c = index % 64u;
  uint packed = GI_SPAWN(j);
  if (packed == kGiNoProbe) return;
  uint cur = gi_parity(GF);
  uvec2 seed = gi_unpack(packed);
  uint tile = gi_tile_of(GF, seed);
  uint nt64 = gi_tiles(GF) * 64u;
  Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed));
  GiFrame fx = gi_frame(px.ng);
  float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
  vec3 w = gi_texel_direction(fx, c);
  vec4 acc = GI_RADIANCE(source * nt64 + tile * 64u + c);
  float weight = 1.0f;
  float d = acc.w;
  ivec2 dir = pass == 0u ? ivec2(1, 0) : ivec2(0, 1);
  for (int k = 0; k < 6; ++k) {
    int step = (k / 2 + 1) * ((k & 1) == 0 ? -1 : 1);
    uint q = gi_find_probe(GI_CTX seed, dir * step);
    if (q == kGiNoProbe || q == packed) continue;
    uvec2 qs = gi_unpack(q);
    Gi10Pixel pq = gi_pixel(GI_CTX cur, gi_pixel_index(GF, qs));
    if (abs(dot3(pq.position - px.position, px.ng)) > cs || dot3(w, pq.ng) < 0.0f) continue;
    GiFrame fq = gi_frame(pq.ng);
    uint cq = gi_texel_of(fq, w);
    vec3 wq = gi_texel_direction(fq, cq);
    vec4 vq = GI_RADIANCE(source * nt64 + (gi_tile_of(GF, qs)) * 64u + cq);
    float dq = min(vq.w, d);
    SST_PRECISE vec3 h = pq.position + wq * dq;
    if (dot3(w, normalize3(h - px.position)) < GF.filter_angle) continue;
    float wz = gi_pow8(gi_saturate(1.0f - abs(pq.depth - px.depth) / px.depth));
    acc += gi_vec4(gi_scrub(gi_rgb(vq)) * wz, dq * wz);
    weight += wz;
    d = acc.w / weight;
  }
  GI_RADIANCE(target * nt64 + tile * 64u + c) = acc / weight;
}

SST_FUNC void gi_stage_copy_probes(GI_CTX_PARAM uint source, uint target, uint index) {
  uint nt64 = gi_tiles(GF) * 64u;
  GI_RADIANCE(target * nt64 + index) = GI_RADIANCE(source * nt64 + index);
}

// ---- S18: project a traced probe onto L2 spherical harmonics --------------------------------------
SST_FUNC void gi_stage_project(GI_CTX_PARAM uint j) {
  uint packed = GI_SPAWN(j);
  if (packed == kGiNoProbe) return;
  uint cur = gi_parity(GF);
  uvec2 seed = gi_unpack(packed);
  uint tile = gi_tile_of(GF, seed);
  GiFrame fx = gi_frame(gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed)).ng);
  vec3 sh[9];
  for (uint k = 0u; k < 9u; ++k) sh[k] = vec3(0.0f);
  for (uint c = 0u; c < 64u; ++c) {
    vec3 l = gi_rgb(GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c));
    vec3 w = gi_texel_direction(fx, c);
    for (uint k = 0u; k < 9u; ++k) sh[k] += l * (GF.sh_weight * gi_sh_basis(k, w));
  }
  for (uint k = 0u; k < 9u; ++k) GI_SH(cur * gi_tiles(GF) * 9u + tile * 9u + k) = gi_vec4(sh[k], 1.0f);
}

// ---- S19: each pixel's irradiance from up to four probes ------------------------------------------
SST_FUNC vec3 gi_probe_irradiance(GI_CTX_PARAM uint tile, vec3 ns) {
  uint base = gi_parity(GF) * gi_tiles(GF) * 9u + tile * 9u;
  vec3 e = vec3(0.0f);
  for (uint k = 0u; k < 9u; ++k) e += gi_rgb(GI_SH(base + k)) * gi_sh_cosine(k, ns);
  return max3(e, vec3(0.0f));
}

SST_FUNC void gi_stage_interpolate(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  vec4 out_value = vec4(0.0f);
  if (!gi_sky(px)) {
    uvec2 p = uvec2(index % GF.width, index / GF.width);
    float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
    HashRng rng = gi_rng(GF, GI10_STAGE_INTERPOLATE, index);
    float jx = hash_rng_next(rng);
    float jy = hash_rng_next(rng);
    ivec2 j = ivec2(int((2.0f * jx - 1.0f) * GF.interpolation_jitter), int((2.0f * jy - 1.0f) * GF.interpolation_jitter));
    ivec2 pj = clamp(ivec2(int(p.x), int(p.y)) + j, ivec2(0, 0), ivec2(int(GF.width) - 1, int(GF.height) - 1));
    Gi10Pixel pjx = gi_pixel(GI_CTX cur, gi_pixel_index(GF, uvec2(uint(pj.x), uint(pj.y))));
    uvec2 search = p;
    if (!gi_sky(pjx) && abs(dot3(pjx.position - px.position, px.ng)) < 0.5f * cs) search = uvec2(uint(pj.x), uint(pj.y));
    uint q[4];
    q[0] = gi_find_probe(GI_CTX search, ivec2(0, 0));
    if (q[0] != kGiNoProbe) {
      uvec2 s0 = gi_unpack(q[0]);
      ivec2 o = ivec2(search.x < s0.x ? -1 : 1, search.y < s0.y ? -1 : 1);
      q[1] = gi_find_probe(GI_CTX search, ivec2(o.x, 0));
      q[2] = gi_find_probe(GI_CTX search, ivec2(0, o.y));
      q[3] = gi_find_probe(GI_CTX search, o);
      float w[4];
      float wsum = 0.0f;
      float found = 0.0f;
      for (uint i = 0u; i < 4u; ++i) {
        w[i] = -1.0f;  // -1: no probe, or a duplicate of an earlier one
        if (q[i] == kGiNoProbe) continue;
        bool duplicate = false;
        for (uint k = 0u; k < i; ++k) duplicate = duplicate || q[k] == q[i];
        if (duplicate) continue;
        Gi10Pixel pq = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(q[i])));
        w[i] = 0.0f;
        found += 1.0f;
        if (abs(dot3(pq.position - px.position, px.ng)) > cs) continue;
        w[i] = gi_pow8(gi_saturate(1.0f - abs(pq.depth - px.depth) / px.depth) * max(dot3(px.ng, pq.ng), 0.0f));
        wsum += w[i];
      }
      // With no probe on the pixel's surface, every found probe counts alike ("relaxed"), and the
      // denoiser is told not to trust the sample (hint 0).
      float hint = wsum > 0.0f ? 1.0f : 0.0f;
      vec3 e = vec3(0.0f);
      for (uint i = 0u; i < 4u; ++i) {
        if (w[i] < 0.0f) continue;
        float wi = wsum > 0.0f ? w[i] / wsum : 1.0f / found;
        if (wi > 0.0f) {
          uvec2 s = gi_unpack(q[i]);
          e += wi * gi_probe_irradiance(GI_CTX gi_tile_of(GF, s), gi_ns(px));
        }
      }
      out_value = gi_vec4(e, hint);
    }
  }
  GI_DENOISE(index) = out_value;
}

// ---- S20: GI-1.0's denoiser: reprojected history with a variable length, then a blur whose radius
// shrinks as the history grows --------------------------------------------------------------------
SST_FUNC float gi_history_count(vec4 h) { return abs(h.w); }
SST_FUNC vec3 gi_history_mean(vec4 h) { return gi_rgb(h) / max(abs(h.w), 1.0f); }

SST_FUNC void gi_stage_denoise_reproject(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  uint prev = cur ^ 1u;
  uint n = gi_pixels(GF);
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  vec4 e = GI_DENOISE(index);
  vec4 h = vec4(0.0f);
  float delta = 0.0f;
  float beta = 1.0f;
  uvec2 p = uvec2(index % GF.width, index / GF.width);
  if (gi_sky(px)) {
    GI_DENOISE((1u + cur) * n + index) = vec4(0.0f);
    GI_AUX(cur * n + index) = vec4(0.0f, -1.0f, -1.0f, 0.0f);
    return;
  }
  vec2 q;
  float distance;
  if (GF.has_history != 0u && project_to_pixel(GF.previous_view, px.position, q, distance) && q.x >= 0.0f &&
      q.y >= 0.0f && q.x < float(GF.width) && q.y < float(GF.height)) {
    vec3 v = normalize3(GF.view.eye - px.position);
    float graze = 1.0f - max(dot3(v, gi_ns(px)), 0.0f);
    float graze2 = graze * graze;
    float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe) * (1.0f + 4.0f * graze2 * graze2 * graze2);
    vec4 hs = vec4(0.0f);
    float ds = 0.0f;
    float ws = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        int sx = int(floor(q.x)) + dx;
        int sy = int(floor(q.y)) + dy;
        if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
        uint si = uint(sy) * GF.width + uint(sx);
        vec4 hp = GI_DENOISE((1u + prev) * n + si);
        if (hp.w < 1.0f) continue;
        Gi10Pixel pp = gi_pixel(GI_CTX prev, si);
        if (gi_sky(pp) || !(length3(px.position - pp.position) < cs) || !(dot3(gi_ns(px), gi_ns(pp)) > 0.95f)) continue;
        float ddx = float(sx) + 0.5f - q.x;
        float ddy = float(sy) + 0.5f - q.y;
        float wt = gi_saturate(1.0f - sqrt(ddx * ddx + ddy * ddy) / 1.41421356f);
        hs += hp * wt;
        ds += GI_AUX(prev * n + si).x * wt;
        ws += wt;
      }
    }
    if (ws > 0.0f) {
      h = hs / ws;
      delta = ds / ws;
    }
    if (e.w > 0.0f) {
      float lh = luminance(gi_history_mean(h));
      delta = delta + (luminance(gi_rgb(e)) - lh - delta) * 0.125f;
      beta = gi_saturate(1.0f - abs(delta) / max(lh, 1e-4f));
    }
  }
  float mask = max(8.0f - gi_history_count(h), 0.0f);
  // A trusted sample (hint 1) is added to the history (replacing relaxed ones); a relaxed one only
  // where nothing trusted is kept, counted negative.
  if (e.w > 0.0f) {
    if (h.w < 0.0f) h = vec4(0.0f);
    h += gi_vec4(gi_rgb(e), 1.0f);
  } else if (h.w < 1.0f) {
    h += gi_vec4(gi_rgb(e), -1.0f);
  }
  float u = (float(p.x) + 0.5f) / float(GF.width);
  float v = (float(p.y) + 0.5f) / float(GF.height);
  float vign = sqrt(sqrt(max(15.0f * u * (1.0f - v) * v * (1.0f - u), 0.0f)));
  float count = gi_history_count(h);
  float cap = max((4.0f + (GF.denoise_history * min(count, 8.0f) - 4.0f) * beta) * vign, 1.0f);
  if (count > cap) h = h * (cap / count);
  GI_DENOISE((1u + cur) * n + index) = h;
  GI_AUX(cur * n + index) = vec4(delta, mask, mask, 0.0f);
}

// Dilates the blur mask over 9x9 pixels with a linear falloff; counts the blur's work.
SST_FUNC void gi_stage_blur_mask(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  uint n = gi_pixels(GF);
  vec4 aux = GI_AUX(cur * n + index);
  if (aux.y < 0.0f) return;  // sky
  int px = int(index % GF.width);
  int py = int(index / GF.width);
  bool capsaicin = (GF.flags & GI10_BLUR_MASK_CAPSAICIN) != 0u;
  float m = aux.y;
  for (int dy = -4; dy <= 4; ++dy) {
    for (int dx = -4; dx <= 4; ++dx) {
      if (capsaicin ? (dx == 0 || dy == 0) : (dx == 0 && dy == 0)) continue;
      int sx = px + dx;
      int sy = py + dy;
      if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
      float tap = GI_AUX(cur * n + uint(sy) * GF.width + uint(sx)).y;
      float falloff = gi_saturate(1.0f - sqrt(float(dx * dx + dy * dy)) / (4.0f * 1.41421356f));
      m = max(m, floor(tap * falloff + 0.5f));
    }
  }
  aux.z = m;
  GI_AUX(cur * n + index) = aux;
  uint r = uint(m);
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_BLUR_WORK), (2u * r + 1u) * (2u * r + 1u));
}

// One pass of the separable blur (pass 0 along x from the history into the scratch, pass 1 along y
// back into the history), of radius shrinking with the history and with the frame's total work.
// Pass 1 writes E_out, the history's mean.
SST_FUNC void gi_stage_filter_gi(GI_CTX_PARAM uint pass, uint index) {
  uint cur = gi_parity(GF);
  uint n = gi_pixels(GF);
  uint history_base = (1u + cur) * n;  // in DENOISE
  uint scratch = 2u * n;          // in AUX
  vec4 h = pass == 0u ? GI_DENOISE(history_base + index) : GI_AUX(scratch + index);
  float m = GI_AUX(cur * n + index).z;
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  int radius = 0;
  if (m > 0.0f) {
    float work = float(GI_COUNTERS(GI10_COUNT_BLUR_WORK)) / float(n);
    float off = max(0.5f * sqrt(max(work - 25.0f, 0.0f)) - 1.0f, 0.0f);
    radius = int(max(m - off, 1.0f) + 0.5f);
  }
  vec4 result = h;
  if (radius > 0 && !gi_sky(px)) {
    bool history = h.w > 0.0f;
    float k = history ? 200.0f : 20.0f;
    vec3 sum = gi_history_mean(h);
    float wsum = 1.0f;
    int x = int(index % GF.width);
    int y = int(index / GF.width);
    for (int r = -radius; r <= radius; ++r) {
      int sx = pass == 0u ? x + r : x;
      int sy = pass == 0u ? y : y + r;
      if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
      uint si = uint(sy) * GF.width + uint(sx);
      vec4 hq = pass == 0u ? GI_DENOISE(history_base + si) : GI_AUX(scratch + si);
      if (!(hq.w > 0.0f)) continue;
      Gi10Pixel pq = gi_pixel(GI_CTX cur, si);
      if (gi_sky(pq)) continue;
      float w = gi_exp2_negative(-k * abs(1.0f - px.depth / pq.depth));
      if (history) {
        float c = max(dot3(gi_ns(px), gi_ns(pq)), 0.0f);
        w *= (c * c) * (c * c);
      }
      sum += gi_history_mean(hq) * w;
      wsum += w;
    }
    result = gi_vec4(sum / wsum * max(abs(h.w), 1.0f), h.w);
  }
  if (pass == 0u) {
    GI_AUX(scratch + index) = result;
  } else {
    GI_DENOISE(history_base + index) = result;
    GI_OUTPUT(index) = gi_vec4(gi_history_mean(result), h.w);
  }
}

// The radiance the next frame's feedback reads: this frame's image without the emission seen (the
// direct pass and the caches both add it otherwise). The host has put the image in FEEDBACK.
SST_FUNC void gi_stage_feedback_image(GI_CTX_PARAM uint index) {
  vec3 c = gi_rgb(GI_FEEDBACK(index)) - gi_rgb(GI_EMISSION(index));
  GI_FEEDBACK(index) = gi_vec4(max3(c, vec3(0.0f)), 0.0f);
}

// Element `index` of stage `stage` (GI10_STAGE_*): the one entry both backends call. `pass`: the
// mask level of MASK_MIP, the direction of FILTER and FILTER_GI.
SST_FUNC void gi10_stage(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint stage, uint pass, uint index) {
  uint cur = gi_parity(GF);
  if (stage == GI10_STAGE_GBUFFER) gi_stage_gbuffer(SCENE_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_PURGE) gi_stage_purge(GI_CTX index);
  else if (stage == GI10_STAGE_REPROJECT) gi_stage_reproject(GI_CTX index);
  else if (stage == GI10_STAGE_SPAWN) gi_stage_spawn(GI_CTX index);
  else if (stage == GI10_STAGE_EMPTY_TILES) gi_stage_empty_tiles(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_COUNT) gi_stage_list_count(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_SCAN) gi_stage_list_scan(GI_CTX index);
  else if (stage == GI10_STAGE_LIST_COMPACT) gi_stage_list_compact(GI_CTX index);
  else if (stage == GI10_STAGE_PATCH) gi_stage_patch(GI_CTX index);
  else if (stage == GI10_STAGE_SAMPLE) gi_stage_sample(GI_CTX index);
  else if (stage == GI10_STAGE_TRACE) gi_stage_trace(SCENE_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_SHADE) gi_stage_shade(SCENE_CTX LIGHT_CTX RAY_CTX GI_CTX index);
  else if (stage == GI10_STAGE_UPDATE) gi_stage_update(GI_CTX index);
  else if (stage == GI10_STAGE_RESOLVE) gi_stage_resolve(GI_CTX index);
  else if (stage == GI10_STAGE_BLEND) gi_stage_blend(GI_CTX index);
  else if (stage == GI10_STAGE_MASK_MIP) gi_stage_mask_mip(GI_CTX pass, index);
  else if (stage == GI10_STAGE_COPY_PROBES) gi_stage_copy_probes(GI_CTX cur, cur ^ 1u, index);
  else if (stage == GI10_STAGE_FILTER) gi_stage_filter(GI_CTX pass, pass == 0u ? cur : cur ^ 1u, pass == 0u ? cur ^ 1u : cur, index);
  else if (stage == GI10_STAGE_PROJECT) gi_stage_project(GI_CTX index);
  else if (stage == GI10_STAGE_INTERPOLATE) gi_stage_interpolate(GI_CTX index);
  else if (stage == GI10_STAGE_DENOISE_REPROJECT) gi_stage_denoise_reproject(GI_CTX index);
  else if (stage == GI10_STAGE_BLUR_MASK) gi_stage_blur_mask(GI_CTX index);
  else if (stage == GI10_STAGE_FILTER_GI) gi_stage_filter_gi(GI_CTX pass, index);
  else if (stage == GI10_STAGE_FEEDBACK) gi_stage_feedback_image(GI_CTX index);
}

SST_END

#endif  // SST_CORE_GI10_GI10_STAGES_H
