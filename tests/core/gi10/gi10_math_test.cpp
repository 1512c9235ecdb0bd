// GI-1.0's building blocks (core/gi10/gi10_math.h) against their specification and golden values
// (docs/design/gi10.md: tests T1, T2, T3, T5, T6 and T8, and Appendix A, whose values were computed
// independently of sst by Python and C ports of the formulas). Fixed seeds throughout.
#include "core/gi10/gi10_math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "core/rng/hash_rng.h"

namespace sst {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double max_abs_diff(vec3 a, vec3 b) {
  return std::max({std::abs(double(a.x) - b.x), std::abs(double(a.y) - b.y), std::abs(double(a.z) - b.z)});
}

// A uniformly distributed unit vector (double precision, then rounded).
vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    double x = g(rng), y = g(rng), z = g(rng), l = std::sqrt(x * x + y * y + z * z);
    if (l > 1e-6) return vec3(float(x / l), float(y / l), float(z / l));
  }
}

vec3 texel_centre_direction(uint c) { return gi_texel_local_direction(c, vec2(0.5f, 0.5f)); }

// ---- T1: the equal-area hemi-octahedral map and the probe frame ---------------------------------

TEST(Gi10HemiMap, TexelCentresRoundTrip) {
  double worst = 0.0;
  for (uint c = 0; c < kGiProbeTexels; ++c) {
    vec2 uv((float(c & 7u) + 0.5f) / 8.0f, (float(c >> 3u) + 0.5f) / 8.0f);
    vec3 d = gi_hemi_direction(uv);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f) << c;
    EXPECT_GT(d.z, 0.0f) << c;
    vec2 back = gi_hemi_uv(d);
    worst = std::max({worst, std::abs(double(back.x) - uv.x), std::abs(double(back.y) - uv.y)});
    EXPECT_EQ(gi_texel_of_local(d), c);
    EXPECT_EQ(max_abs_diff(texel_centre_direction(c), d), 0.0) << c;
  }
  EXPECT_LE(worst, 1e-6);
}

TEST(Gi10HemiMap, RandomDirectionsRoundTrip) {
  std::mt19937 rng(101);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    vec3 w = random_unit(rng);
    w.z = std::abs(w.z);
    vec2 uv = gi_hemi_uv(w);
    ASSERT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f) << i;
    worst = std::max(worst, max_abs_diff(gi_hemi_direction(uv), w));
    // The lower hemisphere folds onto the upper one.
    vec2 folded = gi_hemi_uv(vec3(w.x, w.y, -w.z));
    ASSERT_EQ(folded.x, uv.x);
    ASSERT_EQ(folded.y, uv.y);
  }
  EXPECT_LE(worst, 1e-5);
  // And the other way: random (u, v) through a direction and back.
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  double worst_uv = 0.0;
  for (int i = 0; i < 100000; ++i) {
    vec2 uv(u01(rng), u01(rng));
    vec2 back = gi_hemi_uv(gi_hemi_direction(uv));
    worst_uv = std::max({worst_uv, std::abs(double(back.x) - uv.x), std::abs(double(back.y) - uv.y)});
  }
  EXPECT_LE(worst_uv, 1e-5);
}

// Directions close to the normal: with r^2 = 1 - |z| taken literally, z's rounding (3e-8 at 1)
// would leave r nothing but noise there, and every direction within 2.4e-4 rad would land on the
// map's centre (texel 36 for any azimuth).
TEST(Gi10HemiMap, DirectionsNearTheNormalKeepTheirAzimuth) {
  const float azimuths[4][2] = {{0.6f, 0.8f}, {-0.8f, 0.6f}, {-0.6f, -0.8f}, {0.8f, -0.6f}};
  std::set<uint> texels;
  for (double theta : {1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2}) {
    for (const auto& a : azimuths) {
      double s = std::sin(theta);
      vec3 w(float(s * a[0]), float(s * a[1]), float(std::cos(theta)));
      EXPECT_LE(max_abs_diff(gi_hemi_direction(gi_hemi_uv(w)), w), 1e-6) << theta;
      // The texel of the same azimuth at 0.03 rad, still one of the four around the pole.
      uint expected =
          gi_texel_of_local(vec3(float(0.03 * a[0]), float(0.03 * a[1]), float(std::sqrt(1.0 - 0.03 * 0.03))));
      EXPECT_EQ(gi_texel_of_local(w), expected) << theta << " " << a[0] << " " << a[1];
      texels.insert(gi_texel_of_local(w));
    }
  }
  EXPECT_EQ(texels.size(), 4u);  // the four texels around the pole
}

// Equal area: a grid uniform in (z, phi) has cells of equal solid angle; binned by
// gi_texel_of_local, every texel gets 2 pi / 64 of the hemisphere.
TEST(Gi10HemiMap, TexelSolidAnglesAreEqual) {
  const int nz = 2048, nphi = 8192;
  std::vector<uint64_t> count(kGiProbeTexels, 0);
  for (int i = 0; i < nz; ++i) {
    double z = (i + 0.5) / nz, s = std::sqrt(1.0 - z * z);
    for (int j = 0; j < nphi; ++j) {
      double phi = 2.0 * kPiD * (j + 0.5) / nphi;
      ++count[gi_texel_of_local(vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)))];
    }
  }
  const double cell = 2.0 * kPiD / (double(nz) * nphi), expected = 2.0 * kPiD / 64.0;
  double worst = 0.0;
  for (uint c = 0; c < kGiProbeTexels; ++c) {
    double omega = count[c] * cell;
    worst = std::max(worst, std::abs(omega / expected - 1.0));
    EXPECT_NEAR(omega, expected, 0.002 * expected) << "texel " << c;
  }
  RecordProperty("max_relative_deviation", std::to_string(worst));
}

TEST(Gi10Frame, OrthonormalAndRightHanded) {
  std::mt19937 rng(202);
  std::vector<vec3> normals = {vec3(1, 0, 0),  vec3(-1, 0, 0), vec3(0, 1, 0),
                               vec3(0, -1, 0), vec3(0, 0, 1),  vec3(0, 0, -1)};
  // Near the axes, down to components whose squares underflow.
  for (float e : {1e-3f, 1e-8f, 1e-15f, 1e-19f, 1e-23f, 1e-30f, 1e-40f}) {
    for (int axis = 0; axis < 3; ++axis) {
      for (float sign : {1.0f, -1.0f}) {
        vec3 n(e, -e, e);
        n[axis] = sign;
        normals.push_back(glm::normalize(n));
        vec3 m(0.0f);
        m[axis] = sign;
        m[(axis + 1) % 3] = e;  // one small component, the other exactly 0
        normals.push_back(glm::normalize(m));
      }
    }
  }
  for (int i = 0; i < 100000; ++i) normals.push_back(random_unit(rng));
  for (const vec3& n : normals) {
    GiFrame f = gi_frame(n);
    ASSERT_EQ(f.n, n);
    ASSERT_TRUE(std::isfinite(f.b1.x) && std::isfinite(f.b1.y) && std::isfinite(f.b1.z))
        << n.x << " " << n.y << " " << n.z;
    ASSERT_NEAR(glm::length(f.b1), 1.0f, 1e-6f) << n.x << " " << n.y << " " << n.z;
    ASSERT_NEAR(glm::length(f.b2), 1.0f, 1e-6f) << n.x << " " << n.y << " " << n.z;
    ASSERT_NEAR(glm::dot(f.b1, f.b2), 0.0f, 1e-6f);
    ASSERT_NEAR(glm::dot(f.b1, n), 0.0f, 1e-6f);
    ASSERT_NEAR(glm::dot(f.b2, n), 0.0f, 1e-6f);
    ASSERT_LE(max_abs_diff(glm::cross(f.b1, f.b2), n), 1e-6);  // right-handed
  }
  // Capsaicin's frame of +z: b1 = (0, -1, 0), b2 = n x b1 = (1, 0, 0).
  GiFrame z = gi_frame(vec3(0, 0, 1));
  EXPECT_EQ(z.b1, vec3(0, -1, 0));
  EXPECT_EQ(z.b2, vec3(1, 0, 0));
}

TEST(Gi10Frame, TexelDirectionsRoundTripInWorldSpace) {
  std::mt19937 rng(303);
  for (int i = 0; i < 2000; ++i) {
    vec3 n = random_unit(rng);
    GiFrame f = gi_frame(n);
    for (uint c = 0; c < kGiProbeTexels; ++c) {
      vec3 w = gi_texel_direction(f, c);
      ASSERT_GT(glm::dot(w, n), 0.0f);
      ASSERT_EQ(gi_texel_of(f, w), c) << i;
      ASSERT_LE(max_abs_diff(gi_to_local(f, w), texel_centre_direction(c)), 1e-6);
    }
  }
}

// ---- T2: L2 spherical harmonics ------------------------------------------------------------------

// Radiance L(local direction) projected over the 64 texel centres of a probe with normal +z
// (frame of gi_frame), then the clamped-cosine irradiance at normal m.
template <class Radiance>
double probe_irradiance(Radiance radiance, double weight, vec3 m) {
  GiFrame f = gi_frame(vec3(0.0f, 0.0f, 1.0f));
  double coeff[9] = {};
  for (uint c = 0; c < kGiProbeTexels; ++c) {
    vec3 d = texel_centre_direction(c);
    vec3 w = gi_to_world(f, d);
    for (uint k = 0; k < 9; ++k) coeff[k] += weight * radiance(d) * gi_sh_basis(k, w);
  }
  double e = 0.0;
  for (uint k = 0; k < 9; ++k) e += coeff[k] * gi_sh_cosine(k, m);
  return e;
}

vec3 tilted(double degrees) {
  double t = degrees * kPiD / 180.0;
  return vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

TEST(Gi10Sh, ProbeProjectionMatchesAppendixA2) {
  auto one = [](vec3) { return 1.0; };
  auto cosine = [](vec3 d) { return double(d.z); };
  const double w = 2.0 * kPiD / 64.0;
  const vec3 up(0.0f, 0.0f, 1.0f);
  auto near_rel = [](double got, double want, double rel) { return std::abs(got / want - 1.0) <= rel; };
  EXPECT_PRED3(near_rel, probe_irradiance(one, w, up) / kPiD, 1.02104, 1e-4);
  EXPECT_PRED3(near_rel, probe_irradiance(cosine, w, up), 2.12001, 1e-4);
  EXPECT_PRED3(near_rel, probe_irradiance(one, w, tilted(30)), 2.9843, 1e-4);
  EXPECT_PRED3(near_rel, probe_irradiance(one, w, tilted(60)), 2.3786, 1e-4);
  EXPECT_PRED3(near_rel, probe_irradiance(one, 0.125, up), 4.08417, 1e-4);
  EXPECT_PRED3(near_rel, probe_irradiance(cosine, 0.125, up), 2.69928, 1e-4);
  const double small_tilts[4][2] = {{1, 1.02096}, {3, 1.02031}, {5, 1.01902}, {10, 1.01296}};
  for (const auto& t : small_tilts) EXPECT_PRED3(near_rel, probe_irradiance(one, w, tilted(t[0])) / kPiD, t[1], 1e-4);
}

// A full-sphere midpoint quadrature in (theta, phi), 512 x 1024.
template <class F>
void sphere_quadrature(F f) {
  const int nt = 512, np = 1024;
  for (int i = 0; i < nt; ++i) {
    double theta = kPiD * (i + 0.5) / nt, st = std::sin(theta), ct = std::cos(theta);
    double dw = st * (kPiD / nt) * (2.0 * kPiD / np);
    for (int j = 0; j < np; ++j) {
      double phi = 2.0 * kPiD * (j + 0.5) / np;
      f(vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct)), dw);
    }
  }
}

// The real SH basis with double-precision constants (Capsaicin's signs and order), as the
// independent port that computed Appendix A.2 has it.
TEST(Gi10Sh, BasisMatchesTheReferenceTable) {
  std::mt19937 rng(343);
  for (int i = 0; i < 10000; ++i) {
    vec3 d = random_unit(rng);
    double x = d.x, y = d.y, z = d.z;
    const double ref[9] = {0.2820947917738781,
                           -0.48860251190292 * y,
                           0.4886025119029199 * z,
                           -0.48860251190292 * x,
                           0.5462742152960395 * (2 * x * y),
                           -1.092548430592079 * z * y,
                           0.9461746957575601 * z * z - 0.3153915652525201,
                           -1.092548430592079 * z * x,
                           0.5462742152960395 * (x * x - y * y)};
    const double band[9] = {kPiD,     2 * kPiD / 3, 2 * kPiD / 3, 2 * kPiD / 3, kPiD / 4,
                            kPiD / 4, kPiD / 4,     kPiD / 4,     kPiD / 4};
    for (uint k = 0; k < 9; ++k) {
      ASSERT_NEAR(gi_sh_basis(k, d), ref[k], 3e-6) << k;
      ASSERT_NEAR(gi_sh_cosine(k, d), band[k] * ref[k], 1e-5) << k;
    }
  }
}

TEST(Gi10Sh, BasisIsOrthonormal) {
  double gram[9][9] = {};
  sphere_quadrature([&](vec3 d, double dw) {
    float y[9];
    for (uint k = 0; k < 9; ++k) y[k] = gi_sh_basis(k, d);
    for (int a = 0; a < 9; ++a)
      for (int b = a; b < 9; ++b) gram[a][b] += double(y[a]) * y[b] * dw;
  });
  for (int a = 0; a < 9; ++a)
    for (int b = a; b < 9; ++b) EXPECT_NEAR(gram[a][b], a == b ? 1.0 : 0.0, 1e-4) << a << "," << b;
}

TEST(Gi10Sh, ClampedCosineProjectsToTheLobeCoefficients) {
  std::mt19937 rng(404);
  for (int trial = 0; trial < 8; ++trial) {
    vec3 n = random_unit(rng);
    double coeff[9] = {};
    sphere_quadrature([&](vec3 d, double dw) {
      double c = std::max(0.0, double(glm::dot(d, n)));
      for (uint k = 0; k < 9; ++k) coeff[k] += c * gi_sh_basis(k, d) * dw;
    });
    for (uint k = 0; k < 9; ++k) EXPECT_NEAR(coeff[k], gi_sh_cosine(k, n), 1e-4) << "trial " << trial << " k " << k;
  }
}

// ---- T3: Halton spawn jitter ---------------------------------------------------------------------

TEST(Gi10Halton, SpawnJitterMatchesAppendixA3) {
  const uint expected[5][2] = {{8, 5}, {4, 10}, {12, 1}, {2, 7}, {10, 12}};
  const uint quadrant[5][2] = {{1, 0}, {0, 1}, {1, 0}, {0, 0}, {1, 1}};
  std::set<uint> visited;
  for (uint f = 0; f < 5; ++f) {
    uvec2 j = gi_spawn_jitter(f, kGiSpawnTile);
    EXPECT_EQ(j.x, expected[f][0]) << "frame " << f;
    EXPECT_EQ(j.y, expected[f][1]) << "frame " << f;
    EXPECT_EQ(j.x / 8u, quadrant[f][0]) << "frame " << f;
    EXPECT_EQ(j.y / 8u, quadrant[f][1]) << "frame " << f;
    visited.insert((j.y / 8u) * 2u + j.x / 8u);
  }
  EXPECT_EQ(visited.size(), 4u);  // every 8x8 screen tile of the spawn tile within frames 0..4
  vec2 h = gi_halton(0);
  EXPECT_EQ(h.x, 0.5f);
  EXPECT_NEAR(h.y, 1.0f / 3.0f, 1e-7f);
  for (uint f = 0; f < 1024; ++f) {
    uvec2 a = gi_spawn_jitter(f, 16u), b = gi_spawn_jitter(f + 256u, 16u), p = gi_spawn_jitter(f, 8u);
    ASSERT_EQ(a, b) << f;  // period 256
    ASSERT_LT(a.x, 16u);
    ASSERT_LT(a.y, 16u);
    // Patched probes use min(floor(8 h), 7): the same Halton point on the 8x8 tile.
    ASSERT_EQ(p, uvec2(a.x / 2u, a.y / 2u)) << f;
  }
  // Within one period the sequence does not repeat early.
  std::set<std::pair<uint, uint>> distinct;
  for (uint f = 0; f < 256; ++f) distinct.insert({gi_spawn_jitter(f, 16u).x, gi_spawn_jitter(f, 16u).y});
  EXPECT_GT(distinct.size(), 200u);
}

// ---- T5: hysteresis -------------------------------------------------------------------------------

TEST(Gi10Hysteresis, MatchesAppendixA4) {
  const float table[][3] = {{1, 1, 0.0f},      {2, 1, 0.0f},    {3, 1, 0.1111f}, {4, 1, 0.25f}, {10, 1, 0.64f},
                            {100, 1, 0.9025f}, {1, 0, 0.9025f}, {0, 1, 0.0f},    {1, 2, 0.0f},  {0, 0, 0.0f}};
  for (const auto& row : table) EXPECT_NEAR(gi_hysteresis(row[0], row[1]), row[2], 1e-4f) << row[0] << " " << row[1];
  // S14's blend value = (1 - a) new + a history, on a step 0 -> 1 over successive refreshes.
  const float step[4] = {0.0975f, 0.4152f, 0.9832f, 1.0f};
  float v = 0.0f;
  for (float want : step) {
    float a = gi_hysteresis(1.0f, v);
    v = (1.0f - a) * 1.0f + a * v;
    EXPECT_NEAR(v, want, 1e-4f);
  }
  // Steady-state means for i.i.d. inputs of true mean 1 (Appendix A.4: 0.401 and 0.995).
  std::mt19937 rng(505);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::normal_distribution<float> gauss(1.0f, 0.3f);
  double bernoulli = 0.0, gaussian = 0.0;
  float vb = 1.0f, vg = 1.0f;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    float xb = u01(rng) < 0.5f ? 2.0f : 0.0f, ab = gi_hysteresis(xb, vb);
    vb = (1.0f - ab) * xb + ab * vb;
    bernoulli += vb;
    float xg = std::max(0.0f, gauss(rng)), ag = gi_hysteresis(xg, vg);
    vg = (1.0f - ag) * xg + ag * vg;
    gaussian += vg;
  }
  EXPECT_NEAR(bernoulli / n, 0.401, 0.01);
  EXPECT_NEAR(gaussian / n, 0.995, 0.005);
  // Bounded: never above the 0.95^2 cap, never negative, for any magnitudes.
  for (int i = 0; i < 10000; ++i) {
    float l1 = std::exp(20.0f * u01(rng) - 10.0f), l2 = std::exp(20.0f * u01(rng) - 10.0f);
    float a = gi_hysteresis(l1, l2);
    ASSERT_GE(a, 0.0f);
    ASSERT_LE(a, 0.9025f + 1e-6f);
    if (l1 <= 2.0f * l2) {
      ASSERT_EQ(a, 0.0f) << l1 << " " << l2;
    }
  }
}

// ---- T6: hashes and the cell descriptor ---------------------------------------------------------

GiCellKey make_key(uint level, int cx, int cy, int cz, uint dx, uint dy, uint dz, uint b) {
  GiCellKey k;
  k.level = level;
  k.tile = uvec3(uint(cx), uint(cy), uint(cz));
  k.dir = uvec3(dx, dy, dz);
  k.short_ray = b;
  return k;
}

TEST(Gi10Hash, MatchesAppendixA1) {
  EXPECT_EQ(pcg_hash(0u), 129708002u);
  EXPECT_EQ(pcg_hash(1u), 2831084092u);
  EXPECT_EQ(gi_xx(0u), 878055299u);
  EXPECT_EQ(gi_xx(1u), 2491795611u);
  struct Golden {
    GiCellKey key;
    uint bucket, checksum;
  };
  const Golden golden[] = {
      {make_key(7, 0, 0, 0, 2, 2, 4, 0), 481u, 0x77398862u},
      {make_key(7, 0, 0, 0, 2, 2, 4, 1), 845u, 0xB59A5914u},
      {make_key(9, -3, 5, 12, 0, 2, 2, 1), 2818u, 0x819D5346u},
      {make_key(6, 100, -200, 300, 4, 2, 2, 0), 1975u, 0xFD175F02u},
      {make_key(10, -1, -1, -1, 2, 0, 2, 0), 3437u, 0x3A8C8220u},
  };
  for (const Golden& g : golden) {
    EXPECT_EQ(gi_key_bucket(g.key, 4096u), g.bucket) << g.key.level;
    EXPECT_EQ(gi_key_checksum(g.key), g.checksum) << g.key.level;
  }
}

TEST(Gi10CellAddress, DirectionBins) {
  EXPECT_EQ(gi_direction_bin(0.0f), 2u);
  EXPECT_EQ(gi_direction_bin(1.0f), 4u);
  EXPECT_EQ(gi_direction_bin(-1.0f), 0u);
  EXPECT_EQ(gi_direction_bin(0.5f), 3u);
  EXPECT_EQ(gi_direction_bin(-0.5f), 1u);
  EXPECT_EQ(gi_direction_bin(0.2499f), 2u);
  EXPECT_EQ(gi_direction_bin(0.25f), 3u);  // bins' edges at odd multiples of 1/4
  GiCellAddress a =
      gi_cell_address(vec3(0.0f), vec3(1.0f, 2.0f, 3.0f), vec3(0.0f, 0.0f, 1.0f), 1.0f, 0.05f, 0.1f, -10, false);
  EXPECT_EQ(a.key.dir, uvec3(2u, 2u, 4u));
  // Unit vectors give 74 distinct codes.
  std::mt19937 rng(606);
  std::set<uint> codes;
  for (int i = 0; i < 2000000; ++i) {
    vec3 w = random_unit(rng);
    codes.insert(gi_direction_bin(w.x) * 25u + gi_direction_bin(w.y) * 5u + gi_direction_bin(w.z));
  }
  EXPECT_EQ(codes.size(), 74u);
}

TEST(Gi10CellAddress, DominantAxisTiesResolveXThenYThenZ) {
  // A point whose cell offsets are e = (1, 2, 3) in its tile (cell size 2^-10 * 2^L).
  const int base_exp = -10;
  const vec3 eye(0.0f);
  const float k_hash = 0.0f, min_cell = 0.25f;  // s = 0.25: level 8, cell 0.25, tile 2
  const vec3 x2(2.0f + 1.5f * 0.25f, 4.0f + 2.5f * 0.25f, -6.0f + 3.5f * 0.25f);
  auto offset = [&](vec3 w) {
    GiCellAddress a = gi_cell_address(eye, x2, w, 10.0f, k_hash, min_cell, base_exp, true);
    EXPECT_EQ(a.cell_size, 0.25f);
    EXPECT_EQ(a.key.level, 8u);
    EXPECT_EQ(a.key.tile, uvec3(1u, 2u, uint(-3)));
    return a.offset;
  };
  const float h = std::sqrt(0.5f), t = std::sqrt(1.0f / 3.0f);
  EXPECT_EQ(offset(vec3(1, 0, 0)), uvec2(2, 3));   // x dominant -> (e.y, e.z)
  EXPECT_EQ(offset(vec3(0, -1, 0)), uvec2(1, 3));  // y -> (e.x, e.z)
  EXPECT_EQ(offset(vec3(0, 0, 1)), uvec2(1, 2));   // z -> (e.x, e.y)
  EXPECT_EQ(offset(vec3(h, h, 0)), uvec2(2, 3));   // x = y -> x
  EXPECT_EQ(offset(vec3(-h, 0, h)), uvec2(2, 3));  // x = z -> x
  EXPECT_EQ(offset(vec3(0, h, -h)), uvec2(1, 3));  // y = z -> y
  EXPECT_EQ(offset(vec3(t, -t, t)), uvec2(2, 3));  // x = y = z -> x
  EXPECT_EQ(offset(vec3(0.1f, h, -h)), uvec2(1, 3));
}

TEST(Gi10CellAddress, RandomHitsLandInTheirTileAndCell) {
  std::mt19937 rng(707);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::uniform_int_distribution<int> exps(-20, -4);
  int checked = 0, short_rays = 0, min_cells = 0;
  for (int i = 0; i < 200000; ++i) {
    vec3 eye(200.0f * u01(rng) - 100.0f, 200.0f * u01(rng) - 100.0f, 200.0f * u01(rng) - 100.0f);
    vec3 x2 = eye + random_unit(rng) * std::exp2(14.0f * u01(rng) - 6.0f);
    if (i % 7 == 0) x2 = glm::floor(x2 * 16.0f) / 16.0f;  // on cell corners
    vec3 w = random_unit(rng);
    float t = 20.0f * u01(rng), k_hash = 0.01f + 0.06f * u01(rng), min_cell = 0.3f * u01(rng) + 1e-3f;
    int base_exp = exps(rng);
    bool short_bit = (i & 1) != 0;
    GiCellAddress a = gi_cell_address(eye, x2, w, t, k_hash, min_cell, base_exp, short_bit);
    // The level from the double-precision size step (skipping steps within 1e-5 of a power of two).
    double dist = std::sqrt(double(eye.x - x2.x) * (eye.x - x2.x) + double(eye.y - x2.y) * (eye.y - x2.y) +
                            double(eye.z - x2.z) * (eye.z - x2.z));
    double s = std::max(dist * k_hash, double(min_cell)), l = std::log2(s) - base_exp;
    min_cells += s == double(min_cell);
    ASSERT_EQ(a.cell_size, std::ldexp(1.0f, base_exp + int(a.key.level)));  // 2^base_exp times a power of two
    if (std::abs(l - std::round(l)) > 1e-5) {
      ASSERT_EQ(int(a.key.level), int(std::floor(l))) << i;
      ASSERT_LE(a.cell_size, s);
      ASSERT_GT(2.0 * a.cell_size, s);
      ++checked;
    }
    const double cell = a.cell_size, tile = 8.0 * cell;
    int e[3];
    for (int c = 0; c < 3; ++c) {
      int tc = int(a.key.tile[c]);  // two's complement
      ASSERT_LE(tc * tile, double(x2[c])) << i << " axis " << c;
      ASSERT_LT(double(x2[c]), (tc + 1) * tile) << i << " axis " << c;
      e[c] = int(std::floor(double(x2[c]) / cell)) - 8 * tc;
      ASSERT_GE(e[c], 0);
      ASSERT_LE(e[c], 7);
      ASSERT_EQ(a.key.dir[c], uint(std::clamp(std::floor(0.5 + 4.0 * (0.5 * w[c] + 0.5)), 0.0, 4.0)));
    }
    float ax = std::abs(w.x), ay = std::abs(w.y), az = std::abs(w.z);
    uvec2 want = ax >= ay && ax >= az ? uvec2(e[1], e[2]) : (ay >= az ? uvec2(e[0], e[2]) : uvec2(e[0], e[1]));
    ASSERT_EQ(a.offset, want) << i;
    ASSERT_EQ(a.key.short_ray, uint(short_bit && t < tile)) << i;
    short_rays += int(a.key.short_ray);
  }
  EXPECT_GT(checked, 199000);
  EXPECT_GT(short_rays, 1000);
  EXPECT_GT(min_cells, 1000);
}

TEST(Gi10CellAddress, CellIndicesOfATileAreDistinctAndDense) {
  for (uint slot : {0u, 1u, 4095u * 16u}) {
    std::set<uint> cells;
    for (uint mip = 0; mip < 4; ++mip)
      for (uint y = 0; y < 8; ++y)
        for (uint x = 0; x < 8; ++x) cells.insert(gi_cell_index(slot, uvec2(x, y), mip));
    ASSERT_EQ(cells.size(), kGiCellsPerTile);
    EXPECT_EQ(*cells.begin(), slot * kGiCellsPerTile);
    EXPECT_EQ(*cells.rbegin(), slot * kGiCellsPerTile + kGiCellsPerTile - 1u);
  }
  EXPECT_EQ(gi_cell_index(2u, uvec2(7u, 7u), 1u), 2u * 85u + 64u + 3u + 3u * 4u);
}

// ---- T8: the cell's count-capped average (S12) --------------------------------------------------

vec4 update(vec4 value, std::vector<float> batch) {
  float sum = 0.0f;
  for (float b : batch) sum += b;
  return gi_cell_update(value, vec3(sum, 2.0f * sum, 0.5f * sum), float(batch.size()), 16.0f);
}

TEST(Gi10CellUpdate, MatchesAppendixA5) {
  const std::vector<std::vector<float>> batches = {{1.0f}, {1.0f, 3.0f}, {2, 2, 2, 2, 2}, {}, {}, {4.0f}};
  const float mean[] = {1.0f, 1.3333f, 1.4167f, 1.4167f, 1.4167f, 1.7857f};
  const float count[] = {1, 3, 8, 7, 6, 7};
  vec4 v(0.0f);
  for (size_t f = 0; f < batches.size(); ++f) {
    v = update(v, batches[f]);
    EXPECT_NEAR(v.w, count[f], 1e-5f) << "frame " << f;
    EXPECT_NEAR(v.x / v.w, mean[f], 1e-4f) << "frame " << f;
    EXPECT_NEAR(v.y / v.w, 2.0f * mean[f], 2e-4f) << "frame " << f;  // channels independent
    EXPECT_NEAR(v.z / v.w, 0.5f * mean[f], 1e-4f) << "frame " << f;
  }
}

TEST(Gi10CellUpdate, CapSteadyStateAndDecay) {
  // First batch: its mean, its count capped at 16.
  vec4 v = update(vec4(0.0f), std::vector<float>(20, 3.0f));
  EXPECT_FLOAT_EQ(v.w, 16.0f);
  EXPECT_FLOAT_EQ(v.x / v.w, 3.0f);
  // Steady state: an exponential moving average with alpha = 1/16 per frame with samples.
  float mean = 3.0f;
  for (int f = 0; f < 10; ++f) {
    float m = float(f % 3);
    v = update(v, {m, m});
    mean += (m - mean) / 16.0f;
    EXPECT_FLOAT_EQ(v.w, 16.0f);
    EXPECT_NEAR(v.x / v.w, mean, 1e-5f);
  }
  // Without samples the mean stays and the count drops by one per frame, to an empty cell.
  for (int f = 15; f >= 0; --f) {
    v = update(v, {});
    EXPECT_EQ(v.w, float(f));
    if (f > 0) {
      EXPECT_NEAR(v.x / v.w, mean, 1e-5f);
    }
  }
  EXPECT_EQ(v, vec4(0.0f));
  EXPECT_EQ(update(vec4(0.0f), {}), vec4(0.0f));  // an empty cell stays empty
}

// Counts stay integers in 0..16 through any sequence of batches (readback compares summed counts
// with 16), and the mean stays that of the batches when every batch has the same mean.
TEST(Gi10CellUpdate, CountsStayIntegers) {
  std::mt19937 rng(909);
  for (int run = 0; run < 2000; ++run) {
    vec4 v(0.0f);
    for (int f = 0; f < 100; ++f) {
      uint k = rng() % 4u == 0u ? 1u + rng() % 3u : 0u;
      float n = v.w;
      v = gi_cell_update(v, vec3(1.5f * float(k)), float(k), 16.0f);
      ASSERT_EQ(v.w, k > 0u ? std::min(n + float(k), 16.0f) : std::max(n - 1.0f, 0.0f)) << run << " " << f;
      if (v.w > 0.0f) {
        ASSERT_NEAR(v.x / v.w, 1.5f, 1e-5f);
      } else {
        ASSERT_EQ(v.x, 0.0f);
      }
    }
  }
}

// ---- order-independent fixed-point sums -----------------------------------------------------------

double exact_value(uvec2 s) { return double(s.y) * 256.0 + double(s.x) * std::ldexp(1.0, -24); }

TEST(Gi10Fixed, SumsAreOrderIndependentAndExactToTheUnit) {
  std::mt19937 rng(808);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<float> values;
  for (int i = 0; i < 100000; ++i) {
    float v = i % 4 == 0 ? u01(rng) : std::exp2(40.0f * u01(rng) - 24.0f);  // 6e-8 .. 6.6e4 and [0, 1)
    values.push_back(v);
  }
  values.push_back(255.99998f);
  values.push_back(256.0f);
  values.push_back(0.0f);
  double exact = 0.0;
  for (float v : values) {
    uvec2 s = gi_fixed_split(v);
    // Values here are below 2^32.
    ASSERT_LT(s.y, 1u << 24);
    ASSERT_LE(std::abs(exact_value(s) - double(v)), std::ldexp(1.0, -25)) << v;  // rounded to the unit
    ASSERT_LE(std::abs(double(gi_fixed_value(s.x, s.y)) - v), std::ldexp(1.0, -25) + 1e-7 * v) << v;
    exact += v;
  }
  // Accumulate as a GPU would with 32-bit atomics: lo words with their carries into hi.
  auto accumulate = [](const std::vector<float>& vs) {
    uint32_t lo = 0, hi = 0;
    for (float v : vs) {
      uvec2 s = gi_fixed_split(v);
      uint32_t old = lo;
      lo += s.x;
      hi += s.y + (lo < old ? 1u : 0u);
    }
    return std::pair<uint32_t, uint32_t>(lo, hi);
  };
  auto first = accumulate(values);
  uint64_t wide = 0;  // the same as one 64-bit integer
  for (float v : values) {
    uvec2 s = gi_fixed_split(v);
    wide += (uint64_t(s.y) << 32) + s.x;
  }
  EXPECT_EQ(wide, (uint64_t(first.second) << 32) | first.first);
  double fixed_sum = double(first.second) * 256.0 + double(first.first) * std::ldexp(1.0, -24);
  EXPECT_LE(std::abs(fixed_sum - exact), double(values.size()) * std::ldexp(1.0, -24));
  float float_sum = 0.0f;
  for (float v : values) float_sum += v;
  bool float_order_dependent = false;
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(values.begin(), values.end(), rng);
    EXPECT_EQ(accumulate(values), first) << "trial " << trial;
    float s = 0.0f;
    for (float v : values) s += v;
    float_order_dependent |= s != float_sum;
  }
  EXPECT_TRUE(float_order_dependent);  // what the fixed point is for
}

TEST(Gi10Fixed, InvalidAndHugeValues) {
  EXPECT_EQ(gi_fixed_split(std::numeric_limits<float>::quiet_NaN()), uvec2(0u));
  EXPECT_EQ(gi_fixed_split(-1.0f), uvec2(0u));
  EXPECT_EQ(gi_fixed_split(-std::numeric_limits<float>::infinity()), uvec2(0u));
  EXPECT_EQ(gi_fixed_split(-0.0f), uvec2(0u));
  EXPECT_EQ(gi_fixed_split(1e-9f), uvec2(0u));  // below half a unit
  EXPECT_EQ(gi_fixed_split(0.75f), uvec2(0xC00000u, 0u));
  EXPECT_EQ(gi_fixed_split(1000.5f), uvec2(232u * 16777216u + 8388608u, 3u));
  // Capped at kGiFixedMax (about 2^40), whose hi word still fits 32 bits.
  uvec2 cap = gi_fixed_split(kGiFixedMax);
  EXPECT_EQ(gi_fixed_split(std::numeric_limits<float>::infinity()), cap);
  EXPECT_EQ(gi_fixed_split(1e30f), cap);
  EXPECT_EQ(exact_value(cap), double(kGiFixedMax));
  EXPECT_GT(cap.y, 4000000000u);
  EXPECT_EQ(gi_fixed_value(cap.x, cap.y), kGiFixedMax);
}

}  // namespace
}  // namespace sst
