// GI-1.0's stages (docs/design/gi10.md: the paper's S1-S21 but its light grid), each as the work
// of one element (a pixel, a screen tile, a probe, a ray, a hash tile), written once for both
// backends: gi10_method.cpp runs them in oneTBB loops, gpu/shaders/gi10.comp dispatches them.
// Every sum is taken in a fixed order by one invocation, or in fixed point (gi_fixed_split), so
// both backends and every thread count give the same bits.
// The stages live in files by the part of the method they serve: gi10_probes.h (screen probes),
// gi10_side_cache.h (their LRU side cache), gi10_cache.h (the world-space radiance cache),
// gi10_resolve.h (per-pixel irradiance and the denoiser); this file holds what they all read,
// gi10_probe_texels.h a probe's texel sums, and gi10_stages.h the entry both backends call.
//
// Hooks, besides the scene's, lights' and rays' (core/pt/trace_path.h lists those):
//   GI_CTX_PARAM / GI_CTX   the buffers' context parameter and argument (empty in GLSL)
//   GF                      the frame's Gi10Frame
//   GI_PIXELS(i) ... GI_OUTPUT(i)     the buffers listed below, as lvalues
//   GI_ATOMIC_ADD(lvalue, v), GI_ATOMIC_CAS(lvalue, compare, v), GI_ATOMIC_MIN(lvalue, v)   return the old value
//
// Buffer layout (element type, count): PIXELS Gi10Pixel 2 W H (this frame's and the previous, by
// frame parity); EMISSION vec4 W H (emission seen at the pixel centres); MASK uint 2 M (M: all
// mips of the tile grid); RADIANCE vec4 2 Nt 64 (rgb, hit distance; with side_cache 66 S more:
// its slots); SH vec4 2 Nt 9; SPAWN uint gi_spawn_words (spawn list and the patch's lists; with
// side_cache its LRU order, claims and lists after them: gi_side_base); RAYS Gi10Ray Ns 64; HASH uint 2 T (checksums,
// then last-touch frames; with world_restir 3 T more: each reservoir slot's winning ray key this
// frame, then the frame + 2 at which each parity's slot was written); VALUES vec4 T 85; ACCUM uint T 64 kGiAccumWords; DENOISE vec4 3 W H
// (irradiance + hint, history x2); AUX vec4 3 W H (colour delta and blur masks x2, filter
// scratch); FEEDBACK vec4 W H; COUNTERS uint GI10_COUNTERS; OUTPUT vec4 W H (E_out); and, with
// world_restir (else one element each), RAY_RESERVOIRS RestirReservoir Ns 64 (each ray's),
// SLOT_RESERVOIRS RestirReservoir 2 T and SLOT_SURFACES RestirSurface 2 T (a reservoir slot's
// stored reservoir and the cache point it belongs to, by frame parity; T slots, as many as hash
// tiles). No buffer exceeds lavapipe's 128 MiB at 1920 x 1080 with the default cache, and the
// stage binds 32 storage buffers with the scene's, Mesa 22 lavapipe's limit per stage.
#ifndef SST_CORE_GI10_GI10_BUFFERS_H
#define SST_CORE_GI10_GI10_BUFFERS_H
#include "core/gi10/gi10_layout.h"
#include "core/gi10/gi10_math.h"
#include "core/restir/restir_layout.h"
#include "core/rng/hash_rng.h"

#ifdef __cplusplus
namespace sst {
using glsl::Gi10Frame;
using glsl::Gi10Pixel;
using glsl::Gi10Ray;
using glsl::gi10_shade_build;
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

// world_restir: reservoir slot i's word in HASH (the slot's key this frame: slot_keys + i; the
// frame stamp of parity p's entry: slot_keys + T + p T + i).
SST_FUNC uint gi_slot_keys(SST_IN(Gi10Frame) f) { return 2u * gi_hash_tiles(f); }

// SPAWN's words: [0, Ns) the spawn list (packed seed or kGiNoProbe); [Ns, 2Ns) override flags;
// [2Ns, 3Ns) the override list; [3Ns, 3Ns + Nt) empty-tile flags; then the empty list (Nt); then
// the blocks' counts (override blocks, then empty blocks); then the two list lengths; then, with
// side_cache, its words (gi_side_* below).
SST_FUNC uint gi_override_blocks(SST_IN(Gi10Frame) f) { return (gi_spawns(f) + kGiBlock - 1u) / kGiBlock; }
SST_FUNC uint gi_empty_blocks(SST_IN(Gi10Frame) f) { return (gi_tiles(f) + kGiBlock - 1u) / kGiBlock; }
SST_FUNC uint gi_spawn_block_base(SST_IN(Gi10Frame) f) { return 3u * gi_spawns(f) + 2u * gi_tiles(f); }
SST_FUNC uint gi_spawn_words(SST_IN(Gi10Frame) f) {
  return gi_spawn_block_base(f) + gi_override_blocks(f) + gi_empty_blocks(f) + 2u;
}

// side_cache's words in SPAWN, from gi_side_base on, for S slots (S = Nt: a slot per screen tile, as
// the paper's side cache has the probe grid's shape) and K = kGiSideListLength: the LRU order
// (position -> slot) 2 S, two copies by frame parity (a frame reads its own, its reorder writes the
// next frame's); CLAIM S (per slot, the lowest claim key of this frame: gi_side_key); SLOT_TILE S
// (the screen tile the slot's probe projects into, or kGiNoProbe); the tiles' lists Nt K (a
// tile's first K slots in slot order, kGiNoProbe after the last); per spawned probe 2 Ns (the slot
// its evicted predecessor goes to, the slot its own radiance updates); the reorder's block counts
// 2 B (B blocks of kGiBlock positions). In RADIANCE, after the probes' 2 Nt 64: the slots'
// texels S 64, then per slot its probe's position (w = 1 once written) and normal.
SST_FUNC uint gi_side_base(SST_IN(Gi10Frame) f) { return gi_spawn_words(f); }
SST_FUNC uint gi_side_order(SST_IN(Gi10Frame) f, uint parity) { return gi_side_base(f) + parity * f.side_slots; }
SST_FUNC uint gi_side_claims(SST_IN(Gi10Frame) f) { return gi_side_base(f) + 2u * f.side_slots; }
SST_FUNC uint gi_side_slot_tiles(SST_IN(Gi10Frame) f) { return gi_side_base(f) + 3u * f.side_slots; }
SST_FUNC uint gi_side_lists(SST_IN(Gi10Frame) f) { return gi_side_base(f) + 4u * f.side_slots; }
SST_FUNC uint gi_side_probes(SST_IN(Gi10Frame) f) { return gi_side_lists(f) + gi_tiles(f) * kGiSideListLength; }
SST_FUNC uint gi_side_blocks(SST_IN(Gi10Frame) f) { return (f.side_slots + kGiBlock - 1u) / kGiBlock; }
SST_FUNC uint gi_side_block_counts(SST_IN(Gi10Frame) f) { return gi_side_probes(f) + 2u * gi_spawns(f); }
SST_FUNC uint gi_side_texels(SST_IN(Gi10Frame) f) { return 2u * gi_tiles(f) * 64u; }
SST_FUNC uint gi_side_positions(SST_IN(Gi10Frame) f) { return gi_side_texels(f) + f.side_slots * 64u; }
SST_FUNC uint gi_side_normals(SST_IN(Gi10Frame) f) { return gi_side_positions(f) + f.side_slots; }

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

SST_END

#endif  // SST_CORE_GI10_GI10_BUFFERS_H
