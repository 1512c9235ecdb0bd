// Single stages of gi10_stages.h on the CPU (docs/design/gi10.md, tests): the hash grid's
// invariants under forced collisions (T7), the guiding's ray counts against its weights (T4), and
// the side cache's lists, slot allocation and LRU order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>

#include "core/gi10/gi10_cpu.h"
#include "core/gi10/gi10_method.h"

namespace sst {
namespace {

// A hash table of one bucket (every key collides) with 16 slots.
struct OneBucket {
  glsl::Gi10Frame frame{};
  std::vector<uint32_t> hash = std::vector<uint32_t>(32, 0u), counters = std::vector<uint32_t>(GI10_COUNTERS, 0u);
  Gi10Buffers b;
  OneBucket() {
    frame.num_buckets = 1;
    frame.tiles_per_bucket = 16;
    frame.tile_decay = 50;
    b.frame = &frame;
    b.hash = hash.data();
    b.counters = counters.data();
  }
  uint32_t insert(const GiCellKey& k, bool* inserted = nullptr) {
    bool fresh = false;
    uint32_t slot = gi_hash_insert(b, k, fresh);
    if (slot != kGiNoProbe) hash[16 + slot] = frame.frame;  // as the trace stage touches it
    if (inserted) *inserted = fresh;
    return slot;
  }
  void purge() {
    for (uint32_t s = 0; s < 16; ++s) gi_stage_purge(b, s);
  }
};

GiCellKey key(uint32_t i) {
  GiCellKey k;
  k.level = 3;
  k.tile = uvec3(i, 2 * i + 1, 7);
  k.dir = uvec3(2, 2, 4);
  k.short_ray = 0;
  return k;
}

TEST(Gi10HashGrid, SixteenCollidingKeysAreAllFoundAndASeventeenthFails) {
  for (int order = 0; order < 10; ++order) {
    std::vector<uint32_t> ids(16);
    for (uint32_t i = 0; i < 16; ++i) ids[i] = i;
    std::shuffle(ids.begin(), ids.end(), std::mt19937(order));
    OneBucket t;
    std::set<uint32_t> slots;
    for (uint32_t i : ids) {
      bool fresh = false;
      uint32_t s = t.insert(key(i), &fresh);
      ASSERT_NE(s, kGiNoProbe);
      EXPECT_TRUE(fresh);
      slots.insert(s);
    }
    EXPECT_EQ(slots.size(), 16u);  // no key shares a slot
    // Every key is found again, in its own slot, whatever the insertion order was.
    for (uint32_t i = 0; i < 16; ++i) {
      bool fresh = true;
      uint32_t s = t.insert(key(i), &fresh);
      EXPECT_FALSE(fresh);
      EXPECT_EQ(t.hash[s], gi_key_checksum(key(i)));
    }
    EXPECT_EQ(t.insert(key(16)), kGiNoProbe);  // the bucket is full: the ray is lost (and counted)
  }
}

TEST(Gi10HashGrid, ATileLivesFortyNineUntouchedFramesAndIsFreedAtFifty) {
  OneBucket t;
  t.frame.frame = 100;
  uint32_t s = t.insert(key(1));
  t.frame.frame = 149;
  t.purge();
  EXPECT_NE(t.hash[s], 0u);
  t.frame.frame = 150;
  t.purge();
  EXPECT_EQ(t.hash[s], 0u);
  EXPECT_EQ(t.counters[GI10_COUNT_EVICTED], 1u);
}

TEST(Gi10HashGrid, AKeyBehindAFreedSlotIsNotDuplicated) {
  // B6 (docs/design/gi10.md): A in slot 0, B in slot 1; A is freed; inserting B again must find slot 1 (Capsaicin
  // would claim the hole and give B a second tile with empty history).
  OneBucket t;
  uint32_t a = t.insert(key(1)), b = t.insert(key(2));
  t.hash[a] = 0u;
  bool fresh = true;
  EXPECT_EQ(t.insert(key(2), &fresh), b);
  EXPECT_FALSE(fresh);
  EXPECT_EQ(std::count(t.hash.begin(), t.hash.begin() + 16, gi_key_checksum(key(2))), 1);
}

// An 8x8 image (one screen tile) of floor seen from 5 units above, both frame copies alike, with
// the probe of this frame spawned at pixel (3, 3) and a previous probe at the same pixel, from
// whose texels (`radiance`, parity 0) the spawned probe reconstructs its guide.
struct OneProbe {
  static constexpr uint32_t w = 8, h = 8;
  glsl::Gi10Frame frame{};
  std::vector<glsl::Gi10Pixel> pixels = std::vector<glsl::Gi10Pixel>(2 * w * h);
  std::vector<uint32_t> mask = std::vector<uint32_t>(2, gi_pack(uvec2(3, 3))), spawn = std::vector<uint32_t>(8, 0u);
  std::vector<vec4> radiance = std::vector<vec4>(2 * 64, vec4(0.0f));
  std::vector<glsl::Gi10Ray> rays = std::vector<glsl::Gi10Ray>(64);
  Gi10Buffers b;
  OneProbe() {
    frame.width = w;
    frame.height = h;
    frame.tiles_x = frame.tiles_y = 1;
    frame.spawn_x = frame.spawn_y = 1;
    frame.mask_levels = 1;
    frame.k_probe = 1.0f;
    frame.view.eye = vec3(0, 5, 0);
    for (uint32_t i = 0; i < 2 * w * h; ++i) {
      pixels[i].position = vec3(float(i % w) * 0.01f, 0.0f, float((i / w) % h) * 0.01f);
      pixels[i].depth = 5.0f;
      pixels[i].ng = vec3(0, 1, 0);
    }
    spawn[0] = gi_pack(uvec2(3, 3));
    b.frame = &frame;
    b.pixels = pixels.data();
    b.mask = mask.data();
    b.radiance = radiance.data();
    b.spawn = spawn.data();
    b.rays = rays.data();
  }
  // The previous probe's texel c: radiance l(c) in every channel, a miss (direction only, no
  // parallax), in this frame's copy (even frames).
  template <class F>
  void set_guide(F l) {
    for (uint32_t c = 0; c < 64; ++c) radiance[c] = vec4(vec3(l(c)), kGiMissDistance);
  }
};

TEST(Gi10Guiding, RaysPerTexelFollowTheReconstructedLuminanceTimesCosine) {
  // An 8x8 image (one screen tile) of floor; the probe spawned at pixel (3, 3) reconstructs from
  // the reprojected probe at the same pixel, whose texel c holds luminance c % 5 (0 for some), so
  // every lane has history and draws texels in proportion to luminance x cos (never a texel of
  // weight 0). Over 4000 frames' draws the counts match the expectation (chi-square).
  OneProbe p;
  p.frame.flags = GI10_GUIDING;
  p.set_guide([](uint32_t c) { return float(c % 5); });
  std::vector<double> weight(64, 0.0);
  std::vector<double> count(64, 0.0);
  int lanes_with_history = 0;
  for (uint32_t frame = 0; frame < 4000; ++frame) {
    p.frame.frame = 2 * frame;  // parity 0: the buffers above are this frame's
    gi_stage_sample(p.b, 0);
    lanes_with_history = 0;
    for (uint32_t c = 0; c < 64; ++c) {
      count[p.rays[c].texel] += 1.0;
      if (p.rays[c].recon_distance >= 0.0f) ++lanes_with_history;
    }
  }
  ASSERT_EQ(lanes_with_history, 64);  // the probe reprojects onto itself: every texel has history
  double total = 0.0;
  for (uint32_t c = 0; c < 64; ++c) {
    weight[c] = double(c % 5) * gi_texel_local_direction(c, vec2(0.5f, 0.5f)).z;
    total += weight[c];
  }
  double chi2 = 0.0;
  int dof = -1;
  for (uint32_t c = 0; c < 64; ++c) {
    double expected = 4000.0 * 64.0 * weight[c] / total;
    if (expected == 0.0) {
      EXPECT_EQ(count[c], 0.0) << "texel " << c << " has no weight";
      continue;
    }
    chi2 += (count[c] - expected) * (count[c] - expected) / expected;
    ++dof;
  }
  // 51 degrees of freedom: the 0.999 quantile is 90.6.
  EXPECT_LT(chi2, 90.6) << "dof " << dof;
  // The expected rays per texel that texel_estimate expected divides by: the same distribution,
  // summing to the 64 rays.
  double expected_sum = 0.0;
  for (uint32_t c = 0; c < 64; ++c) {
    EXPECT_NEAR(p.rays[c].expected, 64.0 * weight[c] / total, 1e-4) << "texel " << c;
    expected_sum += p.rays[c].expected;
  }
  EXPECT_NEAR(expected_sum, 64.0, 1e-3);
}

TEST(Gi10Guiding, ExpectedTexelsAreUnbiasedWhereTheFillIsNot) {
  // A probe's texel radiance under guiding, averaged over many frames of draws: a texel guiding
  // rarely samples is filled with the mean of the reached ones by the paper's estimate (too
  // bright), while the sum over the expected ray count (texel_estimate expected) averages to the
  // true radiance. True radiance: texel c holds 1 + (c % 5); the guide reconstructs 0.25 + c % 5
  // (wrong, as history is), hysteresis off so each frame stands alone.
  OneProbe p;
  auto mean_texels = [&](uint32_t flags) {
    p.frame.flags = GI10_GUIDING | GI10_BACKUP_MEAN | flags;
    std::vector<double> mean(64, 0.0);
    const int frames = 4000;
    for (int frame = 0; frame < frames; ++frame) {
      p.frame.frame = 2 * uint32_t(frame);
      p.set_guide([](uint32_t c) { return 0.25f + float(c % 5); });  // the blend below overwrites it
      gi_stage_sample(p.b, 0);
      for (uint32_t c = 0; c < 64; ++c) p.rays[c].radiance = vec3(1.0f + float(p.rays[c].texel % 5));
      gi_stage_blend(p.b, 0);
      for (uint32_t c = 0; c < 64; ++c) mean[c] += double(p.radiance[c].x) / frames;
    }
    return mean;
  };
  std::vector<double> fill = mean_texels(0u), expected = mean_texels(GI10_TEXEL_EXPECTED);
  double worst_z = 0.0, fill_dim = 0.0;
  for (uint32_t c = 0; c < 64; ++c) {
    double truth = 1.0 + double(c % 5);
    // The estimate is truth k / n with k the rays landing (mean n, variance at most n): its mean
    // over the frames has a standard deviation of at most truth / sqrt(n frames).
    double n = p.rays[c].expected;
    ASSERT_GT(n, 0.0) << "texel " << c;
    worst_z = std::max(worst_z, std::abs(expected[c] - truth) / (truth / std::sqrt(n * 4000.0)));
    if (c % 5 == 0) fill_dim += fill[c] / truth / 13.0;  // the 13 texels the guide predicts dim
  }
  std::printf("expected texels: worst z %.2f; fill: dim texels %.2f x their radiance\n", worst_z, fill_dim);
  EXPECT_LT(worst_z, 4.5);  // 64 texels: 4.5 standard deviations is a 4e-4 chance by noise
  EXPECT_GT(fill_dim, 1.5);
}

// The side cache's bookkeeping on a grid of tx x ty screen tiles (as many slots) and 2 x 2
// spawned probes; every word of SPAWN's side cache starts at "none".
struct SideCache {
  glsl::Gi10Frame frame{};
  std::vector<uint32_t> spawn, counters = std::vector<uint32_t>(GI10_COUNTERS, 0u);
  std::vector<vec4> radiance;
  Gi10Buffers b;
  SideCache(uint32_t tx, uint32_t ty) {
    frame.tiles_x = tx;
    frame.tiles_y = ty;
    frame.spawn_x = 2;
    frame.spawn_y = 2;
    frame.side_slots = tx * ty;
    frame.frame = 1;
    spawn.assign(gi_side_block_counts(frame) + 2 * gi_side_blocks(frame), kGiNoProbe);
    radiance.assign(gi_side_normals(frame) + frame.side_slots, vec4(0.0f));
    b.frame = &frame;
    b.spawn = spawn.data();
    b.radiance = radiance.data();
    b.counters = counters.data();
  }
  uint32_t& order(uint32_t parity, uint32_t i) { return spawn[gi_side_order(frame, parity) + i]; }
  uint32_t& claim(uint32_t slot) { return spawn[gi_side_claims(frame) + slot]; }
};

// The host sizes SPAWN and RADIANCE (Gi10Sizes) by its own arithmetic; the stages index them by
// gi10_buffers.h's. Both must agree, with the side cache and without, at 1080p.
TEST(Gi10SideCache, TheHostSizesTheBuffersAsTheStagesIndexThem) {
  for (const char* side_cache : {"on", "off"}) {
    Gi10Params p;
    p.side_cache = side_cache;
    const Gi10Sizes s = gi10_sizes(1920, 1080, p);
    glsl::Gi10Frame f{};
    f.tiles_x = s.tiles_x;
    f.tiles_y = s.tiles_y;
    f.spawn_x = s.spawn_x;
    f.spawn_y = s.spawn_y;
    f.side_slots = s.side_slots;
    EXPECT_EQ(s.side_slots, std::string(side_cache) == "on" ? s.tiles() : 0u);
    const uint64_t spawn = f.side_slots > 0 ? gi_side_block_counts(f) + 2 * gi_side_blocks(f) : gi_spawn_words(f);
    EXPECT_EQ(s.spawn_words(), spawn) << side_cache;
    EXPECT_EQ(s.radiance_entries(), uint64_t(gi_side_normals(f)) + f.side_slots) << side_cache;
  }
}

TEST(Gi10SideCache, ATileListsItsLowestSlotsInOrderWhateverTheOrderOfTheirInvocations) {
  SideCache sc(4, 3);
  const uint32_t tile5[] = {11, 3, 7, 1, 9, 4};  // six slots project into tile 5, one into tile 0
  for (uint32_t slot : tile5) sc.spawn[gi_side_slot_tiles(sc.frame) + slot] = 5;
  sc.spawn[gi_side_slot_tiles(sc.frame) + 2] = 0;
  std::mt19937 rng(7);
  std::vector<uint32_t> slots(12);
  for (uint32_t i = 0; i < 12; ++i) slots[i] = i;
  for (uint32_t pass = 1; pass <= kGiSideListLength; ++pass) {
    std::shuffle(slots.begin(), slots.end(), rng);
    for (uint32_t i : slots) gi_stage_side_lookup(sc.b, pass, i);
  }
  const uint32_t* list5 = &sc.spawn[gi_side_lists(sc.frame) + 5 * kGiSideListLength];
  const uint32_t* list0 = &sc.spawn[gi_side_lists(sc.frame)];
  EXPECT_EQ(std::vector<uint32_t>(list5, list5 + 4), (std::vector<uint32_t>{1, 3, 4, 7}));
  EXPECT_EQ(std::vector<uint32_t>(list0, list0 + 4), (std::vector<uint32_t>{2, kGiNoProbe, kGiNoProbe, kGiNoProbe}));
}

TEST(Gi10SideCache, EvictedProbesTakeTheLeastRecentlyUsedSlotsAndTheirClaimsWin) {
  SideCache sc(4, 3);
  const uint32_t lru[] = {5, 9, 2, 0, 1, 3, 4, 6, 7, 8, 10, 11};
  for (uint32_t i = 0; i < 12; ++i) sc.order(1, i) = lru[i];  // frame 1: parity 1
  const uint32_t probes = gi_side_probes(sc.frame);
  sc.spawn[probes + 0] = kGiSideAllocate;  // probe 0 evicted a probe no slot matched
  sc.spawn[probes + 4] = kGiSideAllocate;  // probe 2 too
  sc.spawn[probes + 6] = 5;                // probe 3's evicted probe matched slot 5 ...
  sc.claim(5) = gi_side_key(1u, 3);
  sc.spawn[probes + 3] = 9;                // ... and probe 1's radiance updates slot 9
  sc.claim(9) = gi_side_key(2u, 1);
  gi_stage_side_allocate(sc.b, 0);
  EXPECT_EQ(sc.spawn[probes + 0], 5u);
  EXPECT_EQ(sc.spawn[probes + 4], 9u);
  EXPECT_EQ(sc.claim(5), gi_side_key(0u, 0));  // a taken slot beats the match and the update
  EXPECT_EQ(sc.claim(9), gi_side_key(0u, 2));
  EXPECT_EQ(sc.counters[GI10_COUNT_SIDE_ALLOCATED], 2u);
}

TEST(Gi10SideCache, TheReorderMovesTheWrittenSlotsBackAndKeepsEveryOtherOrder) {
  SideCache sc(30, 20);  // 600 slots: three blocks of the reorder's scan
  const uint32_t n = sc.frame.side_slots;
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  std::mt19937 rng(3);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<uint32_t> unused, used;
  for (uint32_t i = 0; i < n; ++i) {
    sc.order(1, i) = order[i];
    bool written = rng() % 7 == 0;
    if (written) sc.claim(order[i]) = gi_side_key(2u, i);
    (written ? used : unused).push_back(order[i]);
  }
  ASSERT_GT(used.size(), 20u);
  const uint32_t blocks = gi_side_blocks(sc.frame);
  for (uint32_t b = 0; b < blocks; ++b) gi_stage_side_reorder(sc.b, 0, b);
  gi_stage_side_reorder(sc.b, 1, 0);
  for (uint32_t b = blocks; b-- > 0;) gi_stage_side_reorder(sc.b, 2, b);
  std::vector<uint32_t> expected = unused;
  expected.insert(expected.end(), used.begin(), used.end());
  std::vector<uint32_t> next(n);
  for (uint32_t i = 0; i < n; ++i) next[i] = sc.order(0, i);
  EXPECT_EQ(next, expected);
}

}  // namespace
}  // namespace sst
