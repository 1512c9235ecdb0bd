// GI-1.0's least-recently-used side cache of screen probes (the paper's section 2.1.8; `side_cache`).
// Thin geometry makes a tile's probe alternate between two surfaces: each new probe fails the
// cell-size test against the one before it, so it is traced from scratch, unguided and unblended,
// frame after frame. The side cache keeps such an evicted probe in a slot, and the reconstruction
// of later probes (S6) reads the slots whose probes project near them as it reads the reprojected
// grid, so a probe can continue history that is several frames old.
//
// Per frame: S3 (SIDE_LOOKUP) projects every written slot into the screen and lists each tile's
// slots; S6 (the sample stage, gi10_probes.h) reads the 3 x 3 tiles' lists, detects an eviction
// (the tile's previous probe fed no texel), finds the slot the evicted probe matches and the slot
// the new probe matches, and claims them; SIDE_ALLOCATE gives each evicted probe without a match
// the next slot from the front of the LRU order (least recently used first); S14 (the blend stage)
// writes the slots whose claim it won: the evicted probe's radiance into its slot, the new probe's
// into the slot it matched, so cached radiance follows changing light; S15 (SIDE_REORDER) moves
// the slots written this frame to the back of the LRU order.
//
// Where sst departs from Capsaicin, for the same bits on every backend and thread count: claims
// are an atomic minimum of a key (kind, probe index) instead of a compare-exchange race, a taken
// slot's claim beating the others (the paper drops a write to a slot re-allocated this frame);
// slots are taken by a scan over the evicted probes in index order instead of an atomic cursor;
// a tile lists its kGiSideListLength lowest slots, chosen by one atomic minimum per rank, instead
// of an unbounded list in append order; the reorder keeps the written slots' previous relative
// order (Capsaicin orders them by the order of their claims).
#ifndef SST_CORE_GI10_GI10_SIDE_CACHE_H
#define SST_CORE_GI10_GI10_SIDE_CACHE_H
#include "core/gi10/gi10_probe_texels.h"
#include "core/render/reprojection.h"

SST_BEGIN

SST_FUNC uint gi_side_key(uint kind, uint probe) { return (kind << kGiSideKindShift) | probe; }

SST_FUNC bool gi_side_written(GI_CTX_PARAM uint slot) { return GI_RADIANCE(gi_side_positions(GF) + slot).w > 0.0f; }

// ---- S3: slot i (pass 0: resets, projects; pass p >= 1: competes for rank p - 1 of its tile) ----
SST_FUNC void gi_stage_side_lookup(GI_CTX_PARAM uint pass, uint i) {
  if (pass == 0u) {
    if (GF.frame == 0u) {  // fresh buffers: the LRU order starts as the slots' order
      GI_SPAWN(gi_side_order(GF, 0u) + i) = i;
      GI_SPAWN(gi_side_order(GF, 1u) + i) = i;
    }
    GI_SPAWN(gi_side_claims(GF) + i) = kGiNoProbe;
    // Slots and screen tiles are as many: slot i's invocation clears tile i's list.
    for (uint k = 0u; k < kGiSideListLength; ++k) GI_SPAWN(gi_side_lists(GF) + i * kGiSideListLength + k) = kGiNoProbe;
    uint tile = kGiNoProbe;
    if (gi_side_written(GI_CTX i)) {
      vec2 q;
      float distance;
      vec3 x = gi_rgb(GI_RADIANCE(gi_side_positions(GF) + i));
      if (project_to_pixel(GF.view, x, q, distance) && q.x >= 0.0f && q.y >= 0.0f && q.x < float(GF.width) &&
          q.y < float(GF.height))
        tile = (uint(q.y) / 8u) * GF.tiles_x + uint(q.x) / 8u;
    }
    GI_SPAWN(gi_side_slot_tiles(GF) + i) = tile;
    return;
  }
  uint tile_of_slot = GI_SPAWN(gi_side_slot_tiles(GF) + i);
  if (tile_of_slot == kGiNoProbe) return;
  uint list = gi_side_lists(GF) + tile_of_slot * kGiSideListLength;
  // After pass p - 1 the list holds the tile's p - 1 lowest slots; the lowest slot above them wins.
  if (pass >= 2u && !(i > GI_SPAWN(list + pass - 2u))) return;
  GI_ATOMIC_MIN(GI_SPAWN(list + pass - 1u), i);
}

// ---- S6's part: the cached probes around a new probe --------------------------------------------
// The new probe at px (frame fx, cell size cs) adds the texels of the slots listed in the 3 x 3
// tiles around its tile to its sums, as it adds its reprojected neighbours'. It returns the slot
// its own radiance will update (the closest whose normal is within reproject_normal of its own),
// and, when `evicted` (the tile's previous probe at pe, cell size cse, fed no texel), the slot that
// previous probe matches by the same tests, or kGiSideAllocate; kGiNoProbe for none.
SST_FUNC uvec2 gi_side_reconstruct(GI_CTX_PARAM SST_INOUT(GiTexelSums) a, SST_IN(Gi10Pixel) px, SST_IN(GiFrame) fx,
                                   float cs, uvec2 tile, bool evicted, SST_IN(Gi10Pixel) pe, float cse,
                                   SST_INOUT(bool) fed) {
  uint update = kGiNoProbe;
  uint match = kGiNoProbe;
  float update_distance = 3.0e38f;
  float match_distance = 3.0e38f;
  fed = false;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      int qx = int(tile.x) + dx;
      int qy = int(tile.y) + dy;
      if (qx < 0 || qy < 0 || qx >= int(GF.tiles_x) || qy >= int(GF.tiles_y)) continue;
      uint list = gi_side_lists(GF) + (uint(qy) * GF.tiles_x + uint(qx)) * kGiSideListLength;
      for (uint k = 0u; k < kGiSideListLength; ++k) {
        uint slot = GI_SPAWN(list + k);
        if (slot == kGiNoProbe) break;
        vec3 xc = gi_rgb(GI_RADIANCE(gi_side_positions(GF) + slot));
        vec3 nc = gi_rgb(GI_RADIANCE(gi_side_normals(GF) + slot));
        if (abs(dot3(xc - px.position, px.ng)) < cs) {
          GiFrame fc = gi_frame(nc);
          for (uint c = 0u; c < 64u; ++c)
            if (gi_sums_add_reprojected(a, px.position, px.ng, fx, xc, fc, c,
                                        GI_RADIANCE(gi_side_texels(GF) + slot * 64u + c), false))
              fed = true;
          float d = length3(xc - px.position);
          if (dot3(px.ng, nc) > GF.reproject_normal && d < update_distance) {
            update_distance = d;
            update = slot;
          }
        }
        if (evicted && abs(dot3(xc - pe.position, pe.ng)) < cse && dot3(pe.ng, nc) > GF.reproject_normal) {
          float d = length3(xc - pe.position);
          if (d < match_distance) {
            match_distance = d;
            match = slot;
          }
        }
      }
    }
  }
  return uvec2(evicted ? (match != kGiNoProbe ? match : kGiSideAllocate) : kGiNoProbe, update);
}

// ---- SIDE_ALLOCATE: one invocation gives the evicted probes without a match their slots ---------
// In probe order, from the front of this frame's LRU order; an evicted probe beyond the slots
// keeps none.
SST_FUNC void gi_stage_side_allocate(GI_CTX_PARAM uint index) {
  if (index != 0u) return;
  uint order = gi_side_order(GF, gi_parity(GF));
  uint taken = 0u;
  for (uint j = 0u; j < gi_spawns(GF); ++j) {
    uint at = gi_side_probes(GF) + 2u * j;
    if (GI_SPAWN(at) != kGiSideAllocate) continue;
    if (taken < GF.side_slots) {
      uint slot = GI_SPAWN(order + taken);
      GI_SPAWN(at) = slot;
      GI_ATOMIC_MIN(GI_SPAWN(gi_side_claims(GF) + slot), gi_side_key(0u, j));
      ++taken;
    } else {
      GI_SPAWN(at) = kGiNoProbe;
    }
  }
  GI_COUNTERS(GI10_COUNT_SIDE_ALLOCATED) = taken;
}

// ---- S14's part: probe j writes the slots whose claim it won -------------------------------------
// Before the blend overwrites the tile: the evicted probe's radiance and place (its seed `old`).
SST_FUNC void gi_side_store_evicted(GI_CTX_PARAM uint j, uint tile, uint old) {
  uint slot = GI_SPAWN(gi_side_probes(GF) + 2u * j);
  if (slot == kGiNoProbe || old == kGiNoProbe) return;
  uint claim = GI_SPAWN(gi_side_claims(GF) + slot);
  if (claim != gi_side_key(0u, j) && claim != gi_side_key(1u, j)) return;
  uint cur = gi_parity(GF);
  Gi10Pixel pe = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(old)));
  for (uint c = 0u; c < 64u; ++c)
    GI_RADIANCE(gi_side_texels(GF) + slot * 64u + c) = GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c);
  GI_RADIANCE(gi_side_positions(GF) + slot) = gi_vec4(pe.position, 1.0f);
  GI_RADIANCE(gi_side_normals(GF) + slot) = gi_vec4(pe.ng, 0.0f);
}

// After the blend: the new probe's radiance and place into the slot it matched.
SST_FUNC void gi_side_store_updated(GI_CTX_PARAM uint j, uint tile, SST_IN(Gi10Pixel) px) {
  uint slot = GI_SPAWN(gi_side_probes(GF) + 2u * j + 1u);
  if (slot == kGiNoProbe || GI_SPAWN(gi_side_claims(GF) + slot) != gi_side_key(2u, j)) return;
  uint cur = gi_parity(GF);
  for (uint c = 0u; c < 64u; ++c)
    GI_RADIANCE(gi_side_texels(GF) + slot * 64u + c) = GI_RADIANCE(cur * gi_tiles(GF) * 64u + tile * 64u + c);
  GI_RADIANCE(gi_side_positions(GF) + slot) = gi_vec4(px.position, 1.0f);
  GI_RADIANCE(gi_side_normals(GF) + slot) = gi_vec4(px.ng, 0.0f);
}

// ---- S15: the LRU order of the next frame: slots not written this frame first, then the written ---
// pass 0: block b's counts of both; pass 1 (one invocation): their first positions; pass 2: block b
// moves its slots there, each kind in its previous order.
SST_FUNC void gi_stage_side_reorder(GI_CTX_PARAM uint pass, uint b) {
  uint cur = gi_parity(GF);
  uint order = gi_side_order(GF, cur);
  uint next = gi_side_order(GF, cur ^ 1u);
  uint counts = gi_side_block_counts(GF);
  uint blocks = gi_side_blocks(GF);
  uint first = b * kGiBlock;
  uint last = min(first + kGiBlock, GF.side_slots);
  if (pass == 0u) {
    uint unused = 0u;
    for (uint i = first; i < last; ++i)
      if (GI_SPAWN(gi_side_claims(GF) + GI_SPAWN(order + i)) == kGiNoProbe) ++unused;
    GI_SPAWN(counts + b) = unused;
    GI_SPAWN(counts + blocks + b) = (last - first) - unused;
  } else if (pass == 1u) {
    if (b != 0u) return;
    uint sum = 0u;
    for (uint k = 0u; k < 2u * blocks; ++k) {
      uint c = GI_SPAWN(counts + k);
      GI_SPAWN(counts + k) = sum;
      sum += c;
    }
  } else {
    uint unused_at = GI_SPAWN(counts + b);
    uint used_at = GI_SPAWN(counts + blocks + b);
    for (uint i = first; i < last; ++i) {
      uint slot = GI_SPAWN(order + i);
      if (GI_SPAWN(gi_side_claims(GF) + slot) == kGiNoProbe) {
        GI_SPAWN(next + unused_at) = slot;
        ++unused_at;
      } else {
        GI_SPAWN(next + used_at) = slot;
        ++used_at;
      }
    }
  }
}

SST_END

#endif  // SST_CORE_GI10_GI10_SIDE_CACHE_H
