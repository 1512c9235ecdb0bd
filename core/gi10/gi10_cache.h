// GI-1.0's world-space radiance cache (a hash grid of cells sized by their distance to the eye;
// docs/design/gi10.md): freeing tiles untouched for a while, tracing probe rays into cells, the
// radiance leaving a cache point (last frame's image where it was on screen, else a light
// sample, or with world_restir a reservoir of light samples reused over frames in world space),
// folding the frame's samples into the cells and their mips, and reading the cache back into the
// probe rays.
#ifndef SST_CORE_GI10_GI10_CACHE_H
#define SST_CORE_GI10_GI10_CACHE_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/gi10/gi10_buffers.h"
#include "core/render/pinhole.h"
#include "core/render/reprojection.h"
#include "core/restir/restir_di_stages.h"
#include "core/restir/restir_gi_stages.h"

SST_BEGIN

// ---- S1: free the hash tiles untouched for tile_decay frames ---------------------------------------
SST_FUNC void gi_stage_purge(GI_CTX_PARAM uint slot) {
  if ((GF.flags & GI10_WORLD_RESTIR) != 0u) GI_HASH(gi_slot_keys(GF) + slot) = 0xFFFFFFFFu;  // no reservoir won yet
  if (GI_HASH(slot) == 0u) return;
  uint age = GF.frame - GI_HASH(gi_hash_tiles(GF) + slot);
  if (age >= GF.tile_decay) {
    GI_HASH(slot) = 0u;
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_EVICTED), 1u);
  } else {
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_LIVE_TILES), 1u);
  }
}

// ---- S7: trace a probe ray and find (or make) its cache cell ----------------------------------------
// Linear probing that never duplicates a key: the whole bucket is searched before a free slot is
// taken (Capsaicin takes the first free slot, which after an eviction can give one key two tiles).
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
  r.lift = s.lift;
  r.offset = s.offset;
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

// The cache point of ray r as ReSTIR's surface: x2 seen along the probe ray, Lambertian with its
// base colour as GI-1.0 shades it.
SST_FUNC RestirSurface gi_cache_surface(SST_IN(Gi10Ray) r) {
  RestirSurface s;
  s.p = r.x2;
  s.offset = r.offset;
  s.ng = r.n2;
  s.metallic = 0.0f;
  s.ns = r.ns2;
  s.roughness = 1.0f;
  s.base_color = r.albedo2;
  s.hit = 1u;
  s.lift = r.lift;
  s.depth = r.t;
  s.dir = r.direction;
  s.pad0 = 0.0f;
  return s;
}

// A cache point's world-space ReSTIR slot: the position of its hash tile (level and tile
// coordinates: 8 x 8 x 8 cells, without the ray's direction, as the light arriving at a point does
// not depend on where it is seen from), hashed into the slots, direct-mapped: a collision costs
// reuse only, as the merge checks that the stored point is near. A cell alone gets too few rays a
// frame at batch resolutions (cells of 2 pixels at 72 rows: 15% of the Cornell box's cache points
// found a reservoir, 72% with tiles).
SST_FUNC uint gi_reservoir_slot(GI_CTX_PARAM SST_IN(Gi10Ray) r) {
  GiCellAddress a = gi_cell_address(GF.view.eye, r.x2, r.direction, r.t, GF.k_hash, GF.min_cell, GF.hash_base_exp, false);
  uint h = pcg_hash(a.key.tile.x);
  h = pcg_hash(a.key.tile.y + h);
  h = pcg_hash(a.key.tile.z + h);
  return pcg_hash(a.key.level + h) % gi_hash_tiles(GF);
}

// A ray's key in the contest for its reservoir slot: distinct for every ray of a frame (an odd
// multiplier is a bijection of 32 bits), so the lowest wins on every backend and thread count
// whatever the order of the atomics.
SST_FUNC uint gi_reservoir_key(SST_IN(Gi10Frame) f, uint index) { return index * 2654435761u + gi_xx(f.frame); }

// One light sample at x2 (sst's direct-light estimator, the lights picked as by every method's
// direct pass): a Lambertian reflection toward the probe, unbiased, with no MIS (no BRDF sample to
// weigh). False when no light could be picked.
SST_FUNC bool gi_light_sample(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index, SST_IN(Gi10Ray) r,
                              SST_OUT(vec3) lo) {
  lo = vec3(0.0f);
  HashRng rng = gi_rng(GF, GI10_STAGE_SHADE, index);
  float u1 = hash_rng_next(rng);
  float u2 = hash_rng_next(rng);
  vec2 u = vec2(u1, u2);
  LightSample ls;
  if (!light_sample(SCENE_CTX LIGHT_CTX r.x2, r.ns2, u, ls)) return false;
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
  return true;
}

// World-space ReSTIR at x2 (the paper's section 2.3.1, with sst's reservoirs of core/restir):
// RIS over restir_candidates light samples with visibility reuse, then merged by pairwise MIS
// with the reservoir the previous frame left in the point's slot, where that one's point lies
// within 16 cells (its tile's diagonal) and faces the same way (normals within 25 degrees), its
// M capped at restir_cap times the new one's; visibility reuse again, and the kept sample's
// contribution times W. The reservoir enters the slot's contest (STORE_RESERVOIR). False when no
// light could be picked.
SST_FUNC bool gi_world_restir(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index,
                              SST_INOUT(Gi10Ray) r, SST_OUT(vec3) lo) {
  lo = vec3(0.0f);
  RestirSurface s = gi_cache_surface(r);
  HashRng rng = gi_rng(GF, GI10_STAGE_SHADE, index);
  PathCounters counters = path_counters();
  RestirReservoir canonical = restir_di_initial(SCENE_CTX LIGHT_CTX RAY_CTX s, true, GF.restir_candidates, 0u, rng, counters);
  RestirReservoir kept = canonical;
  uint slots = gi_hash_tiles(GF);
  uint slot = gi_reservoir_slot(GI_CTX r);
  uint prev = (gi_parity(GF) ^ 1u) * slots + slot;
  if (GF.has_history != 0u && GI_HASH(gi_slot_keys(GF) + slots + prev) == GF.frame + 1u) {  // written by the previous frame
    RestirSurface sp = GI_SLOT_SURFACES(prev);
    RestirReservoir rp = GI_SLOT_RESERVOIRS(prev);
    if (dot3(sp.ng, s.ng) > kRestirNormalCosine && length3(sp.p - s.p) < 16.0f * r.cell_size) {
      rp.m = min(rp.m, GF.restir_cap * canonical.m);
      float u_pair = hash_rng_next(rng);
      float u_end = hash_rng_next(rng);
      RestirMerge g = restir_merge_begin(canonical);
      restir_merge_pair(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, sp, rp, 1.0f, true,
                        (GF.flags & GI10_WORLD_RESTIR_UNBIASED) != 0u, u_pair, g, counters);
      kept = restir_merge_end(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, true, u_end, g, counters);
      GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_RESERVOIRS_REUSED), 1u);
    }
  }
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_SHADOW_RAYS), counters.shadow_rays);
  if (kept.light == LIGHT_NONE) return false;
  GI_RAY_RESERVOIRS(index) = kept;
  r.flags |= GI10_RAY_RESERVOIR;
  GI_ATOMIC_MIN(GI_HASH(gi_slot_keys(GF) + slot), gi_reservoir_key(GF, index));
  lo = gi_scrub(restir_shade(SCENE_CTX LIGHT_CTX s, true, kept));
  return true;
}

// cache_shading path: the radiance leaving x2 toward the probe by a path traced along the probe
// ray (`pt`'s path, next-event estimation at every vertex, Russian roulette after 3 bounces from
// the pixel), x2's emission left out as the direct pass has it: every bounce, where a light sample
// gives the first only. The exact form of what the feedback image approximates for the points it
// shows, and the light of the points it does not show. False when the path finds no surface.
SST_FUNC bool gi_cache_path(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM GI_CTX_PARAM uint index, SST_IN(Gi10Ray) r,
                            SST_OUT(vec3) lo) {
  lo = vec3(0.0f);
  Gi10Pixel px = gi_pixel(GI_CTX gi_parity(GF), gi_pixel_index(GF, gi_unpack(GI_SPAWN(index / 64u))));
  PixelSampler ps = pixel_sampler(GF.seed ^ kGiPathSeed, index, GF.frame);
  PathState st = path_begin(offset_ray_origin(GF.scene_epsilon, px.position, px.ng), r.direction, ps);
  trace_path_state(SCENE_CTX LIGHT_CTX RAY_CTX st, restir_gi_path_config(GF.path_bounces, kGiPathRrMinBounces, GF.diffuse_only != 0u));
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_SHADOW_RAYS), st.counters.shadow_rays);
  if (!st.hit) return false;
  lo = gi_scrub(restir_gi_radiance(st.result.direct, st.first_hit.emission, st.result.indirect));
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
#ifdef GI10_SHADER_STAGE
  const uint build = GI10_SHADER_STAGE;  // a SHADE shader holds one way of shading
#else
  const uint build = gi10_shade_build(GF.flags);
#endif
  vec3 lo;
  bool sampled;
  if (build == GI10_SHADER_SHADE_PATHS) sampled = gi_cache_path(SCENE_CTX LIGHT_CTX RAY_CTX GI_CTX index, r, lo);
  else if (build == GI10_SHADER_SHADE_RESTIR) sampled = gi_world_restir(SCENE_CTX LIGHT_CTX RAY_CTX GI_CTX index, r, lo);
  else sampled = gi_light_sample(SCENE_CTX LIGHT_CTX RAY_CTX GI_CTX index, r, lo);
  if (!sampled) {
    GI_RAYS(index) = r;
    return;
  }
  r.flags |= GI10_RAY_SHADOW;
  gi_accumulate(GI_CTX r.cell, lo);
  // A hit closer than a cell would read light from the probe's own surface neighbourhood through
  // the cell: it keeps its own sample instead (the cell is fed all the same). Without the cache
  // lookup every ray does.
  Gi10Pixel px = gi_pixel(GI_CTX gi_parity(GF), gi_pixel_index(GF, gi_unpack(GI_SPAWN(index / 64u))));
  bool own = (GF.flags & GI10_CACHE_LOOKUP) == 0u;
  if (own || ((GF.flags & GI10_BYPASS) != 0u && length3(r.x2 - px.position) < r.cell_size)) {
    r.flags |= GI10_RAY_BYPASS;
    r.radiance += lo;
    GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_BYPASS), 1u);
  }
  GI_RAYS(index) = r;
}

// ---- S10 (world_restir): the ray that won its slot's contest stores its reservoir there ------------
SST_FUNC void gi_stage_store_reservoir(GI_CTX_PARAM uint index) {
  Gi10Ray r = GI_RAYS(index);
  if ((r.flags & GI10_RAY_RESERVOIR) == 0u) return;
  uint slot = gi_reservoir_slot(GI_CTX r);
  if (GI_HASH(gi_slot_keys(GF) + slot) != gi_reservoir_key(GF, index)) return;
  uint slots = gi_hash_tiles(GF);
  uint entry = gi_parity(GF) * slots + slot;
  GI_SLOT_RESERVOIRS(entry) = GI_RAY_RESERVOIRS(index);
  GI_SLOT_SURFACES(entry) = gi_cache_surface(r);
  GI_HASH(gi_slot_keys(GF) + slots + entry) = GF.frame + 2u;
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

SST_END

#endif  // SST_CORE_GI10_GI10_CACHE_H
