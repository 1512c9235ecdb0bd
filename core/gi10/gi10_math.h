// GI-1.0's building blocks (Boisse et al. 2022; specified in docs/design/gi10.md), written once for
// the CPU and the GPU (core/math/cpu_gpu.h): the equal-area hemispherical probe map and the probe
// frame, L2 spherical harmonics, the hash functions and cell descriptor of the world cache, the
// shadow-preserving hysteresis, the cache's count-capped average, the Halton spawn jitter and the
// order-independent fixed-point sums. The stages that use them are gi10_stages.h.
#ifndef SST_CORE_GI10_GI10_MATH_H
#define SST_CORE_GI10_GI10_MATH_H
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"
#include "core/rng/hash_rng.h"

SST_BEGIN

SST_CONSTANT uint kGiProbeSize = 8u;     // probe texels per side = pixels per screen tile side
SST_CONSTANT uint kGiProbeTexels = 64u;  // one ray per texel of a spawned probe
SST_CONSTANT uint kGiSpawnTile = 16u;    // pixels per spawn-tile side: 1/4 ray per pixel
SST_CONSTANT uint kGiNoProbe = 0xFFFFFFFFu;
SST_CONSTANT uint kGiCellsPerTile = 85u;  // 8x8 + 4x4 + 2x2 + 1 cells of one hash tile's mips
SST_CONSTANT float kGiMissDistance = 1e9f;
// texel_estimate expected: the uniform part of guiding's distribution, as a fraction of its mean
// weight (the guided share stays 1 / (1 + kGiGuideFloor) = 80% of the rays).
SST_CONSTANT float kGiGuideFloor = 0.25f;
// The pixel sampler of cache_shading path's paths is seeded apart from every other stream.
SST_CONSTANT uint kGiPathSeed = 0x47495041u;  // "GIPA"
// ... and Russian roulette may end them after this many bounces counted from the pixel, as pt's.
SST_CONSTANT int kGiPathRrMinBounces = 3;
SST_CONSTANT uint kGiAccumWords = 7u;  // per cache cell: 64-bit fixed-point r, g, b, then the count
SST_CONSTANT uint kGiBlock = 256u;     // elements per block of the spawn stage's list compaction
// side_cache: the cached probes a screen tile lists (the lowest slots that project into it), and
// the key of a probe's claim on a slot: its kind times 2^24 plus the probe's index, the lowest
// winning (kind 0: a slot taken from the LRU order, 1: an evicted probe's matching slot, 2: the
// slot a new probe's radiance updates).
SST_CONSTANT uint kGiSideListLength = 4u;
SST_CONSTANT uint kGiSideKindShift = 24u;
SST_CONSTANT uint kGiSideAllocate = 0xFFFFFFFEu;  // an evicted probe that found no slot to match

SST_FUNC float gi_sign(float x) { return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f); }

// ---- the equal-area hemi-octahedral map (Clarberg's): every texel subtends 2 pi / 64 ----------
// (u, v) in [0,1]^2 to a unit direction of the upper hemisphere (z >= 0) of the local frame.
SST_FUNC vec3 gi_hemi_direction(vec2 uv) {
  SST_PRECISE float s = 2.0f * uv.x - 1.0f;
  SST_PRECISE float t = 2.0f * uv.y - 1.0f;
  SST_PRECISE float a = 0.5f * (s + t);
  SST_PRECISE float b = 0.5f * (s - t);
  SST_PRECISE float r = abs(a) + abs(b);
  if (r <= 0.0f) return vec3(0.0f, 0.0f, 1.0f);
  r = min(r, 1.0f);
  SST_PRECISE float phi = 0.25f * kPi * ((abs(b) - abs(a)) / r + 1.0f);
  SST_PRECISE float sin_theta = r * sqrt(max(2.0f - r * r, 0.0f));
  SST_PRECISE float z = 1.0f - r * r;
  SST_PRECISE float x = sin_theta * gi_sign(a) * accurate_cos(phi);
  SST_PRECISE float y = sin_theta * gi_sign(b) * accurate_sin(phi);
  return vec3(x, y, z);
}

// The inverse: a local direction (z >= 0; z < 0 folds onto the hemisphere) to (u, v). Near the
// pole r^2 = 1 - |z| is taken as (x^2 + y^2) / (1 + |z|): 1 - |z| would keep only z's rounding
// there (every direction within 2.4e-4 rad of the normal would map to the centre, texel 36).
SST_FUNC vec2 gi_hemi_uv(vec3 d) {
  SST_PRECISE float az = abs(d.z);
  SST_PRECISE float r2 = az > 0.5f ? (d.x * d.x + d.y * d.y) / (1.0f + az) : 1.0f - az;
  SST_PRECISE float r = sqrt(max(r2, 0.0f));
  SST_PRECISE float phi = accurate_atan2(abs(d.y), abs(d.x)) * (2.0f / kPi);  // in [0, 1]
  SST_PRECISE float tb = phi * r;  // |b|
  SST_PRECISE float ta = r - tb;   // |a|
  SST_PRECISE float a = ta * gi_sign(d.x);
  SST_PRECISE float b = tb * gi_sign(d.y);
  SST_PRECISE float u = 0.5f * (a + b) + 0.5f;
  SST_PRECISE float v = 0.5f * (a - b) + 0.5f;
  return vec2(u, v);
}

// The texel (0..63, row-major, 8 per row) holding local direction d.
SST_FUNC uint gi_texel_of_local(vec3 d) {
  vec2 uv = gi_hemi_uv(d);
  uint cx = uint(clamp(floor(uv.x * 8.0f), 0.0f, 7.0f));
  uint cy = uint(clamp(floor(uv.y * 8.0f), 0.0f, 7.0f));
  return cy * 8u + cx;
}

// The local direction through point `f` ((0.5, 0.5): the centre) of texel `c`.
SST_FUNC vec3 gi_texel_local_direction(uint c, vec2 f) {
  return gi_hemi_direction(vec2((float(c & 7u) + f.x) * 0.125f, (float(c >> 3u) + f.y) * 0.125f));
}

// The probe frame (b1, b2, n) of a unit geometric normal: CPU and GPU must build the same one, or
// a texel would mean another direction on each. Capsaicin swaps x and z when n.z = 0; also when
// n lies within 1e-15 of +-x, where p.z^2 + p.y^2 would underflow (to 0 on a GPU that flushes
// denormals) and k be infinite.
struct GiFrame {
  vec3 b1;
  vec3 b2;
  vec3 n;
};

SST_FUNC GiFrame gi_frame(vec3 n) {
  GiFrame f;
  f.n = n;
  SST_PRECISE float q = n.z * n.z + n.y * n.y;
  bool swap = n.z == 0.0f || q < 1e-30f;
  vec3 p = swap ? vec3(n.z, n.y, n.x) : n;
  SST_PRECISE float k = 1.0f / sqrt(p.z * p.z + p.y * p.y);
  vec3 b = vec3(0.0f, -p.z * k, p.y * k);
  f.b1 = swap ? vec3(b.z, b.y, b.x) : b;
  f.b2 = cross3(n, f.b1);
  return f;
}

SST_FUNC vec3 gi_to_world(SST_IN(GiFrame) f, vec3 d) {
  SST_PRECISE vec3 r = d.x * f.b1 + d.y * f.b2 + d.z * f.n;
  return r;
}

SST_FUNC vec3 gi_to_local(SST_IN(GiFrame) f, vec3 w) { return vec3(dot3(w, f.b1), dot3(w, f.b2), dot3(w, f.n)); }

SST_FUNC vec3 gi_texel_direction(SST_IN(GiFrame) f, uint c) {
  return gi_to_world(f, gi_texel_local_direction(c, vec2(0.5f, 0.5f)));
}

SST_FUNC uint gi_texel_of(SST_IN(GiFrame) f, vec3 w) { return gi_texel_of_local(gi_to_local(f, w)); }

// ---- L2 spherical harmonics (real basis, world space) -------------------------------------------
SST_FUNC float gi_sh_basis(uint k, vec3 d) {
  // precise: a GPU compiler may fuse k6's and k8's multiply-adds, the CPU does not.
  SST_PRECISE float b = 0.546274f * (d.x * d.x - d.y * d.y);
  if (k == 0u) b = 0.282095f;
  else if (k == 1u) b = -0.488603f * d.y;
  else if (k == 2u) b = 0.488603f * d.z;
  else if (k == 3u) b = -0.488603f * d.x;
  else if (k == 4u) b = 1.092548f * d.x * d.y;
  else if (k == 5u) b = -1.092548f * d.y * d.z;
  else if (k == 6u) b = 0.946175f * d.z * d.z - 0.315392f;
  else if (k == 7u) b = -1.092548f * d.x * d.z;
  return b;
}

// The clamped-cosine lobe's band factors (pi, 2 pi / 3, pi / 4) times the basis at normal n: the
// irradiance at n is the sum over k of this times coefficient k.
SST_FUNC float gi_sh_cosine(uint k, vec3 n) {
  float band = k == 0u ? kPi : (k < 4u ? 2.0f * kPi / 3.0f : 0.25f * kPi);
  return band * gi_sh_basis(k, n);
}

// ---- hashes of the world cache (pcg_hash of core/rng; xxHash32's avalanche) ----------------------
SST_FUNC uint gi_xx(uint v) {
  uint r = v + 374761393u;
  r = 668265263u * ((r << 17u) | (r >> 15u));
  r = 2246822519u * (r ^ (r >> 15u));
  r = 3266489917u * (r ^ (r >> 13u));
  return r ^ (r >> 16u);
}

// A hash tile's key: level, tile coordinate, direction code, short-ray bit.
struct GiCellKey {
  uint level;
  uvec3 tile;  // ivec3 reinterpreted (two's complement)
  uvec3 dir;   // 0..4 per axis
  uint short_ray;
};

// H(e1..e8) = h(e1 + h(e2 + ... h(e8))), level first, short-ray bit innermost; h is pcg_hash (the
// bucket) or gi_xx (the checksum).
SST_FUNC uint gi_key_hash_step(uint v, bool xx) { return xx ? gi_xx(v) : pcg_hash(v); }

SST_FUNC uint gi_key_hash(SST_IN(GiCellKey) k, bool xx) {
  uint h = gi_key_hash_step(k.short_ray, xx);
  h = gi_key_hash_step(k.dir.z + h, xx);
  h = gi_key_hash_step(k.dir.y + h, xx);
  h = gi_key_hash_step(k.dir.x + h, xx);
  h = gi_key_hash_step(k.tile.z + h, xx);
  h = gi_key_hash_step(k.tile.y + h, xx);
  h = gi_key_hash_step(k.tile.x + h, xx);
  return gi_key_hash_step(k.level + h, xx);
}

SST_FUNC uint gi_key_bucket(SST_IN(GiCellKey) k, uint num_buckets) { return gi_key_hash(k, false) % num_buckets; }
SST_FUNC uint gi_key_checksum(SST_IN(GiCellKey) k) { return max(gi_key_hash(k, true), 1u); }  // 0: an empty slot

// The direction code of a unit vector: 5 bins per axis centred on -1, -1/2, 0, 1/2, 1.
SST_FUNC uint gi_direction_bin(float w) { return uint(clamp(floor(0.5f + 4.0f * (0.5f * w + 0.5f)), 0.0f, 4.0f)); }

// The power of two 2^e as a float, for e in [-126, 127].
SST_FUNC float gi_exp2i(int e) { return uintBitsToFloat(uint(e + 127) << 23u); }

// floor(log2(x)) of a positive normal float, read from its exponent (the same on both backends).
SST_FUNC int gi_floor_log2(float x) { return int((floatBitsToUint(x) >> 23u) & 0xFFu) - 127; }

// Where a probe ray's hit lands in the world cache. The cell size is view-relative (distance to
// the eye times k_hash, at least min_cell) and a power-of-two multiple of the scene-relative base
// 2^base_exp, so that the divisions below are exact scalings and both backends bin alike.
struct GiCellAddress {
  GiCellKey key;
  uvec2 offset;     // the cell in its tile: the two axes left when the ray's dominant one is dropped
  float cell_size;  // edge of a cell
};

SST_FUNC GiCellAddress gi_cell_address(vec3 eye, vec3 x2, vec3 w, float t, float k_hash, float min_cell, int base_exp,
                                       bool short_ray_bit) {
  GiCellAddress a;
  SST_PRECISE float s = max(length3(eye - x2) * k_hash, min_cell);
  int level = gi_floor_log2(s * gi_exp2i(-base_exp));
  float cell = gi_exp2i(base_exp + level);
  float inv_cell = gi_exp2i(-(base_exp + level));
  float inv_tile = gi_exp2i(-(base_exp + level + 3));
  ivec3 tile = ivec3(int(floor(x2.x * inv_tile)), int(floor(x2.y * inv_tile)), int(floor(x2.z * inv_tile)));
  ivec3 c = ivec3(int(floor(x2.x * inv_cell)), int(floor(x2.y * inv_cell)), int(floor(x2.z * inv_cell)));
  ivec3 e = ivec3(clamp(c.x - 8 * tile.x, 0, 7), clamp(c.y - 8 * tile.y, 0, 7), clamp(c.z - 8 * tile.z, 0, 7));
  a.key.level = uint(level);
  a.key.tile = uvec3(uint(tile.x), uint(tile.y), uint(tile.z));
  a.key.dir = uvec3(gi_direction_bin(w.x), gi_direction_bin(w.y), gi_direction_bin(w.z));
  a.key.short_ray = (short_ray_bit && t < 8.0f * cell) ? 1u : 0u;
  vec3 aw = abs(w);
  if (aw.x >= aw.y && aw.x >= aw.z) {
    a.offset = uvec2(uint(e.y), uint(e.z));
  } else if (aw.y >= aw.z) {
    a.offset = uvec2(uint(e.x), uint(e.z));
  } else {
    a.offset = uvec2(uint(e.x), uint(e.y));
  }
  a.cell_size = cell;
  return a;
}

// The index of a cell of hash tile `slot` at mip m (0..3) within the values array.
SST_FUNC uint gi_cell_index(uint slot, uvec2 offset, uint mip) {
  uint first = mip == 0u ? 0u : (mip == 1u ? 64u : (mip == 2u ? 80u : 84u));
  return slot * kGiCellsPerTile + first + (offset.x >> mip) + (offset.y >> mip) * (8u >> mip);
}

// ---- the probe blend's shadow-preserving hysteresis (paper Algorithm 3, Capsaicin's luminance) --
// The weight of the history given new luminance l1 and history luminance l2: 0 unless the new
// value is more than twice as bright, so darkening is immediate and brightening is damped.
SST_FUNC float gi_hysteresis(float l1, float l2) {
  float a = clamp(max(l1 - l2 - min(l1, l2), 0.0f) / max(max(l1, l2), 1e-4f), 0.0f, 0.95f);
  return a * a;
}

// ---- the cache cell's count-capped average (S12) ------------------------------------------------
// `value`: (mean radiance x count, count); batch: this frame's sum and sample count k. The whole
// batch weighs 1 / min(n + k, cap); a cell of a touched tile without samples loses one count.
SST_FUNC vec4 gi_cell_update(vec4 value, vec3 batch_sum, float k, float cap) {
  float n = value.w;
  vec3 old_mean = n > 0.0f ? vec3(value.x, value.y, value.z) / n : vec3(0.0f);
  vec3 new_mean = k > 0.0f ? batch_sum / k : vec3(0.0f);
  float old_w = n > 0.0f ? 1.0f : 0.0f;
  float new_w = k > 0.0f ? 1.0f : 0.0f;
  float count = min(n + k, cap);
  vec4 r;
  if (n <= 0.0f) {
    r = vec4(new_mean.x, new_mean.y, new_mean.z, new_w);
  } else {
    float a = 1.0f / count;
    r = vec4(old_mean.x + (new_mean.x - old_mean.x) * a, old_mean.y + (new_mean.y - old_mean.y) * a,
             old_mean.z + (new_mean.z - old_mean.z) * a, old_w + (new_w - old_w) * a);
  }
  r = r * count;
  // The count is an integer: count with samples, one less without. The lerp above gives it only
  // to a rounding (13.999999, or -2e-7 for a cell emptied), which would fail "count >= 16" on a
  // mip's sum and leave emptied cells with a residue of negative count and radiance.
  r.w = k > 0.0f ? count : max(count - 1.0f, 0.0f);
  return r;
}

// ---- Halton spawn jitter (bases 2 and 3, period 256, one jitter per frame for all tiles) -------
SST_FUNC float gi_radical_inverse(uint i, uint base) {
  float inv = 1.0f / float(base);
  float f = inv;
  float r = 0.0f;
  while (i > 0u) {
    r += f * float(i % base);
    i /= base;
    f *= inv;
  }
  return r;
}

SST_FUNC vec2 gi_halton(uint frame) {
  uint i = (frame & 255u) + 1u;
  return vec2(gi_radical_inverse(i, 2u), gi_radical_inverse(i, 3u));
}

// The spawn pixel's offset inside a tile of `size` pixels.
SST_FUNC uvec2 gi_spawn_jitter(uint frame, uint size) {
  vec2 h = gi_halton(frame);
  float s = float(size);
  return uvec2(uint(min(floor(s * h.x), s - 1.0f)), uint(min(floor(s * h.y), s - 1.0f)));
}

// ---- order-independent sums: a non-negative float as a 64-bit fixed-point number (2^-24 units) --
// Any thread order adds the same integers, so sums are the same bits on every backend and thread
// count. hi = floor(v / 256) and lo = (v - 256 hi) 2^24 are exact; values below 6e-8 round away and
// a single sample is capped at 2^40.
SST_CONSTANT float kGiFixedMax = 1.0995e12f;

SST_FUNC uvec2 gi_fixed_split(float v) {
  float x = v == v ? clamp(v, 0.0f, kGiFixedMax) : 0.0f;  // NaN counts as 0
  float hi = floor(x * (1.0f / 256.0f));
  SST_PRECISE float rest = x - hi * 256.0f;
  // Rounded half up as floor(y) + (y - floor(y) >= 1/2), both exact: floor(y + 0.5) would round
  // y + 0.5 to even first where y is an odd integer in [2^23, 2^24) (rest in [0.5, 1)), one unit up.
  SST_PRECISE float y = rest * 16777216.0f;
  SST_PRECISE float lo = floor(y);
  lo = min(y - lo >= 0.5f ? lo + 1.0f : lo, 4294967295.0f);
  return uvec2(uint(lo), uint(hi));
}

SST_FUNC float gi_fixed_value(uint lo, uint hi) {
  SST_PRECISE float v = float(hi) * 256.0f + float(lo) * (1.0f / 16777216.0f);
  return v;
}

SST_END

#endif  // SST_CORE_GI10_GI10_MATH_H
