// GI-1.0's screen probes (one per 8 x 8 tile; docs/design/gi10.md): the G-buffer of pixel
// centres they are placed on, their reprojection from the previous frame, spawning and the patch
// that moves rays to disoccluded tiles, ray directions, the hysteresis blend of traced texels, the
// probe mask's mips, the filter across probes and the projection onto spherical harmonics. The
// probe rays' radiance comes from gi10_cache.h.
#ifndef SST_CORE_GI10_GI10_PROBES_H
#define SST_CORE_GI10_GI10_PROBES_H
#include "core/gi10/gi10_side_cache.h"
#include "core/render/pinhole.h"
#include "core/render/reprojection.h"

SST_BEGIN

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
// SPAWN's layout: gi10_buffers.h.

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

// ---- S6: reconstruct a new probe from its reprojected neighbours (and, with side_cache, the cached
// probes around it: gi10_side_cache.h) and choose its ray directions ----------------------------
SST_FUNC void gi_stage_sample(GI_CTX_PARAM uint j) {
  uint cur = gi_parity(GF);
  uint packed = GI_SPAWN(j);
  uint side_probe = gi_side_probes(GF) + 2u * j;
  if (packed == kGiNoProbe) {
    for (uint c = 0u; c < 64u; ++c) GI_RAYS(j * 64u + c).flags = 0u;
    if (GF.side_slots != 0u) {
      GI_SPAWN(side_probe) = kGiNoProbe;
      GI_SPAWN(side_probe + 1u) = kGiNoProbe;
    }
    return;
  }
  uvec2 seed = gi_unpack(packed);
  Gi10Pixel px = gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed));
  GiFrame fx = gi_frame(px.ng);
  float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
  int tx = int(seed.x / 8u);
  int ty = int(seed.y / 8u);
  uint mask_base = cur * gi_mask_total(GF);
  uint own_tile = gi_tile_of(GF, seed);
  uint own_probe = kGiNoProbe;  // the tile's previous probe, which this one replaces
  bool own_fed = false;
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
      if (qt == own_tile) own_probe = q;
      Gi10Pixel pq = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(q)));
      if (!(abs(dot3(pq.position - px.position, px.ng)) <= cs)) continue;
      GiFrame fq = gi_frame(pq.ng);
      for (uint c = 0u; c < 64u; ++c)
        if (gi_sums_add_reprojected(a, px.position, px.ng, fx, pq.position, fq, c,
                                    GI_RADIANCE(cur * gi_tiles(GF) * 64u + qt * 64u + c), false) &&
            qt == own_tile)
          own_fed = true;
    }
  }
  if (GF.side_slots != 0u) {
    // The previous probe of the tile is evicted when it fed none of this one's texels.
    bool evicted = own_probe != kGiNoProbe && !own_fed;
    Gi10Pixel pe = px;
    float cse = cs;
    if (evicted) {
      pe = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(own_probe)));
      cse = gi_cell_size(GF.view.eye, pe.position, GF.k_probe);
    }
    bool fed = false;
    uvec2 slots = gi_side_reconstruct(GI_CTX a, px, fx, cs, uvec2(uint(tx), uint(ty)), evicted, pe, cse, fed);
    GI_SPAWN(side_probe) = slots.x;
    GI_SPAWN(side_probe + 1u) = slots.y;
    if (slots.x != kGiNoProbe && slots.x != kGiSideAllocate)
      GI_ATOMIC_MIN(GI_SPAWN(gi_side_claims(GF) + slots.x), gi_side_key(1u, j));
    if (slots.y != kGiNoProbe) GI_ATOMIC_MIN(GI_SPAWN(gi_side_claims(GF) + slots.y), gi_side_key(2u, j));
    if (evicted) GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_SIDE_EVICTED), 1u);
    if (fed) GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_SIDE_USED), 1u);
  }
  bool history = false;
  for (uint c = 0u; c < 64u; ++c)
    if (a.count[c] > 0.0f) history = true;
  if (!history) GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_NO_HISTORY), 1u);
  // The guiding distribution: reconstructed luminance times the cosine at each texel's centre.
  // texel_estimate expected mixes in a uniform floor (kGiGuideFloor of the mean weight), so every
  // texel keeps a chance: a texel guiding can never reach would keep a dark estimate for ever.
  float cdf[65];
  cdf[0] = 0.0f;
  for (uint c = 0u; c < 64u; ++c) {
    float w = 0.0f;
    if (a.count[c] > 0.0f) w = max(luminance(gi_rgb(a.sum[c])) / a.count[c], 0.0f) * gi_texel_local_direction(c, vec2(0.5f, 0.5f)).z;
    cdf[c + 1u] = cdf[c] + w;
  }
  if ((GF.flags & GI10_TEXEL_EXPECTED) != 0u) {
    SST_PRECISE float floor_weight = cdf[64] * (kGiGuideFloor / 64.0f);
    for (uint c = 1u; c <= 64u; ++c) {
      SST_PRECISE float raised = cdf[c] + floor_weight * float(c);
      cdf[c] = raised;
    }
  }
  float total = cdf[64];
  bool guided_run = (GF.flags & GI10_GUIDING) != 0u && total > 0.0f;
  float guided_lanes = 0.0f;
  for (uint c = 0u; c < 64u; ++c)
    if (guided_run && a.count[c] > 0.0f) guided_lanes += 1.0f;
  for (uint c = 0u; c < 64u; ++c) {
    HashRng rng = gi_rng(GF, GI10_STAGE_SAMPLE, j * 64u + c);
    float u = hash_rng_next(rng);
    // A lane whose own texel had history draws from the distribution; one without explores its
    // own texel (with no weight anywhere, every lane explores its own).
    uint texel = c;
    bool guided = guided_run && a.count[c] > 0.0f;
    if (guided) {
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
    // Texel c receives each guided lane's ray with probability w_c / total, and lane c's own when
    // it explores.
    SST_PRECISE float expected = (guided ? 0.0f : 1.0f) + (guided_run ? guided_lanes * ((cdf[c + 1u] - cdf[c]) / total) : 0.0f);
    r.expected = expected;
    GI_RAYS(j * 64u + c) = r;
  }
}

// ---- S14: a traced probe's texels: the mean of its rays, blended with its reconstruction through
// the shadow-preserving hysteresis (paper Algorithm 3) --------------------------------------------
SST_FUNC void gi_stage_blend(GI_CTX_PARAM uint j) {
  uint packed = GI_SPAWN(j);
  if (packed == kGiNoProbe) return;
  uint cur = gi_parity(GF);
  uvec2 seed = gi_unpack(packed);
  uint tile = gi_tile_of(GF, seed);
  if (GF.side_slots != 0u) gi_side_store_evicted(GI_CTX j, tile, GI_MASK(cur * gi_mask_total(GF) + tile));
  GiTexelSums a;
  gi_sums_clear(a);
  for (uint c = 0u; c < 64u; ++c) {
    Gi10Ray r = GI_RAYS(j * 64u + c);
    vec3 l = gi_scrub(r.radiance);
    a.sum[r.texel] += vec4(l.x, l.y, l.z, r.t);
    a.count[r.texel] += 1.0f;
  }
  vec3 backup = gi_backup(a, (GF.flags & GI10_BACKUP_MEAN) != 0u);
  bool expected = (GF.flags & GI10_TEXEL_EXPECTED) != 0u;
  for (uint c = 0u; c < 64u; ++c) {
    vec4 value = gi_sums_texel(a, c, backup);
    Gi10Ray r = GI_RAYS(j * 64u + c);
    // The unbiased alternative to the paper's fill: the texel's radiance summed over its rays and
    // divided by how many were expected, so a texel guiding rarely samples is 0 mostly and large
    // when hit. A texel no ray could reach (weight 0) keeps its reconstruction.
    if (expected && r.expected > 0.0f)
      value = gi_vec4(gi_rgb(a.sum[c]) / r.expected, a.count[c] > 0.0f ? a.sum[c].w / a.count[c] : kGiMissDistance);
    else if (expected && r.recon_distance >= 0.0f)
      value = gi_vec4(r.recon, r.recon_distance);
    if (r.recon_distance >= 0.0f && (GF.flags & GI10_HYSTERESIS) != 0u) {
      vec4 history = gi_vec4(r.recon, r.recon_distance);
      float alpha = gi_hysteresis(luminance(gi_rgb(value)), luminance(r.recon));
      SST_PRECISE vec4 blended = value + (history - value) * alpha;  // precise: no fused multiply-add on a GPU
      value = blended;
    }
    GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c) = value;
  }
  GI_MASK(cur * gi_mask_total(GF) + tile) = packed;
  if (GF.side_slots != 0u) gi_side_store_updated(GI_CTX j, tile, gi_pixel(GI_CTX cur, gi_pixel_index(GF, seed)));
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
  SST_PRECISE vec3 sh[9];
  for (uint k = 0u; k < 9u; ++k) sh[k] = vec3(0.0f);
  for (uint c = 0u; c < 64u; ++c) {
    vec3 l = gi_rgb(GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c));
    vec3 w = gi_texel_direction(fx, c);
    for (uint k = 0u; k < 9u; ++k) sh[k] += l * (GF.sh_weight * gi_sh_basis(k, w));
  }
  for (uint k = 0u; k < 9u; ++k) GI_SH(cur * gi_tiles(GF) * 9u + tile * 9u + k) = gi_vec4(sh[k], 1.0f);
}

SST_END

#endif  // SST_CORE_GI10_GI10_PROBES_H
