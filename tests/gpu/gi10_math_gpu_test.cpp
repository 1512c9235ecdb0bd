// GI-1.0's building blocks on the GPU (core/gi10/gi10_math.h compiled as GLSL, through
// gpu/shaders/gi10_math_test.comp) against the same source compiled as C++, on the same random
// inputs ("CPU = GPU" means identical integers and floats within a few ulps; docs/design/gi10.md,
// tests): texel
// indices, cell keys and offsets, hashes, fixed-point words and jitters bit for bit; the map's
// directions and uv, the frame, SH, hysteresis and the cell update within 4 ulps or 2^-24 absolute
// at unit scale (measured on lavapipe: 0 ulps everywhere, printed by the test).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/gi10/gi10_math.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst::gpu {
namespace {

constexpr uint32_t kInWords = 44, kOutWords = 64;

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float from_bits(uint32_t u) { return std::bit_cast<float>(u); }

// Distance in representable floats (0 for equal values, +0 and -0 included).
int64_t ulps(float a, float b) {
  if (a == b) return 0;
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
  auto ordered = [](float f) {
    int64_t i = std::bit_cast<int32_t>(f);
    return i < 0 ? int64_t(INT32_MIN) - i : i;
  };
  return std::abs(ordered(a) - ordered(b));
}

vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    double x = g(rng), y = g(rng), z = g(rng), l = std::sqrt(x * x + y * y + z * z);
    if (l > 1e-6) return vec3(float(x / l), float(y / l), float(z / l));
  }
}

// The inputs of record i (kInWords words), varied to reach the special cases: texel centres and
// edges of the map, the pole, axis-aligned and nearly axis-aligned normals, ties of the ray's
// dominant axis, hits on cell corners, empty cells and batches, NaN and huge fixed-point values.
std::vector<uint32_t> make_inputs(uint32_t count) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<uint32_t> in(size_t(count) * kInWords, 0u);
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t* w = &in[size_t(i) * kInWords];
    auto put = [&](int o, float v) { w[o] = bits(v); };
    auto put3 = [&](int o, vec3 v) {
      for (int c = 0; c < 3; ++c) put(o + c, v[c]);
    };
    const uint32_t kind = i % 8u;
    // uv
    vec2 uv(u01(rng), u01(rng));
    if (kind == 1) uv = vec2((float(i % 8u) + 0.5f) / 8.0f, (float((i / 8u) % 8u) + 0.5f) / 8.0f);
    if (kind == 2) uv = vec2(float(rng() % 9u) / 8.0f, float(rng() % 9u) / 8.0f);  // texel edges, 0.5, 0, 1
    put(0, uv.x);
    put(1, uv.y);
    // local direction (both hemispheres), some near the pole or on the axes
    vec3 d = random_unit(rng);
    if (kind == 3) {
      double theta = std::exp2(-24.0 * u01(rng)), phi = 6.283185307 * u01(rng);
      d = vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
    }
    if (kind == 4) {
      d = vec3(0.0f);
      d[rng() % 3u] = u01(rng) < 0.5f ? 1.0f : -1.0f;
    }
    put3(2, d);
    // normal
    vec3 n = random_unit(rng);
    if (kind == 5 || kind == 6) {
      n = vec3(0.0f);
      n[rng() % 3u] = u01(rng) < 0.5f ? 1.0f : -1.0f;
      if (kind == 6) {
        float e = std::exp2(-100.0f * u01(rng));  // down to 8e-31, normal floats only
        for (int c = 0; c < 3; ++c)
          if (n[c] == 0.0f && (rng() & 1u)) n[c] = (rng() & 1u) ? e : -e;
        n = glm::normalize(n);
      }
    }
    put3(5, n);
    // a probe ray's hit
    vec3 eye(200.0f * u01(rng) - 100.0f, 200.0f * u01(rng) - 100.0f, 200.0f * u01(rng) - 100.0f);
    vec3 x2 = eye + random_unit(rng) * std::exp2(14.0f * u01(rng) - 6.0f);
    if (kind == 7) x2 = glm::floor(x2 * 16.0f) / 16.0f;
    vec3 ray = random_unit(rng);
    if (kind == 2) {  // ties of the dominant axis
      const float h = std::sqrt(0.5f), t = std::sqrt(1.0f / 3.0f);
      const vec3 ties[4] = {vec3(h, -h, 0.0f), vec3(-h, 0.0f, h), vec3(0.0f, h, h), vec3(t, t, -t)};
      ray = ties[rng() % 4u];
    }
    put3(8, eye);
    put3(11, x2);
    put3(14, ray);
    put(17, 20.0f * u01(rng));
    put(18, 0.01f + 0.06f * u01(rng));
    put(19, 0.3f * u01(rng) + 1e-3f);
    w[20] = uint32_t(-20 + int(rng() % 17u));
    w[21] = rng() & 1u;
    // hysteresis
    put(22, kind == 1 ? 0.0f : std::exp2(20.0f * u01(rng) - 10.0f));
    put(23, kind == 3 ? 0.0f : std::exp2(20.0f * u01(rng) - 10.0f));
    // a cell and a batch
    float n_old = float(rng() % 17u), k = rng() % 3u == 0u ? 0.0f : float(rng() % 21u);
    vec3 mean(u01(rng), 10.0f * u01(rng), 0.1f * u01(rng)), batch(u01(rng), 5.0f * u01(rng), u01(rng));
    put(24, mean.x * n_old);
    put(25, mean.y * n_old);
    put(26, mean.z * n_old);
    put(27, n_old);
    put3(28, batch * k);
    put(31, k);
    put(32, 16.0f);
    // fixed point
    float v = std::exp2(72.0f * u01(rng) - 30.0f);  // 1e-9 .. 4e12 (above the cap)
    if (kind == 1) v = -v;
    if (i % 97u == 0u) v = std::numeric_limits<float>::quiet_NaN();
    if (i % 89u == 0u) v = std::numeric_limits<float>::infinity();
    if (kind == 5) v = float(rng() % 4096u) / 256.0f;
    put(33, v);
    // a key, a word, a frame
    w[34] = rng() % 32u;
    w[35] = rng();
    w[36] = rng();
    w[37] = rng();
    w[38] = rng() % 5u;
    w[39] = rng() % 5u;
    w[40] = rng() % 5u;
    w[41] = rng() & 1u;
    w[42] = rng();
    w[43] = i;
  }
  return in;
}

// The same record on the CPU, laid out as the shader writes it.
std::vector<uint32_t> cpu_outputs(const uint32_t* w, uint32_t i) {
  auto f = [&](int o) { return from_bits(w[o]); };
  auto f3 = [&](int o) { return vec3(f(o), f(o + 1), f(o + 2)); };
  std::vector<uint32_t> r(kOutWords, 0u);
  auto put3 = [&](int o, vec3 v) {
    for (int c = 0; c < 3; ++c) r[o + c] = bits(v[c]);
  };
  put3(0, gi_hemi_direction(vec2(f(0), f(1))));
  vec2 uv = gi_hemi_uv(f3(2));
  r[3] = bits(uv.x);
  r[4] = bits(uv.y);
  r[5] = gi_texel_of_local(f3(2));
  GiFrame frame = gi_frame(f3(5));
  put3(6, frame.b1);
  put3(9, frame.b2);
  put3(12, frame.n);
  GiCellAddress a = gi_cell_address(f3(8), f3(11), f3(14), f(17), f(18), f(19), int(w[20]), w[21] != 0u);
  const uint32_t key[8] = {a.key.level, a.key.tile.x, a.key.tile.y, a.key.tile.z,
                           a.key.dir.x, a.key.dir.y,  a.key.dir.z,  a.key.short_ray};
  std::copy(key, key + 8, &r[15]);
  r[23] = a.offset.x;
  r[24] = a.offset.y;
  r[25] = bits(a.cell_size);
  r[26] = gi_key_bucket(a.key, 4096u);
  r[27] = gi_key_checksum(a.key);
  GiCellKey k;
  k.level = w[34];
  k.tile = uvec3(w[35], w[36], w[37]);
  k.dir = uvec3(w[38], w[39], w[40]);
  k.short_ray = w[41];
  r[28] = gi_key_bucket(k, 4096u);
  r[29] = gi_key_checksum(k);
  r[30] = pcg_hash(w[42]);
  r[31] = gi_xx(w[42]);
  r[32] = bits(gi_hysteresis(f(22), f(23)));
  vec4 value = gi_cell_update(vec4(f(24), f(25), f(26), f(27)), f3(28), f(31), f(32));
  for (int c = 0; c < 4; ++c) r[33 + c] = bits(value[c]);
  uvec2 s = gi_fixed_split(f(33));
  r[37] = s.x;
  r[38] = s.y;
  r[39] = bits(gi_fixed_value(s.x, s.y));
  uvec2 j = gi_spawn_jitter(w[43], 16u);
  r[40] = j.x;
  r[41] = j.y;
  vec3 dir = gi_texel_direction(frame, i & 63u);
  r[42] = gi_texel_of(frame, dir);
  put3(43, dir);
  for (uint c = 0; c < 9; ++c) r[46 + c] = bits(gi_sh_basis(c, f3(2)));
  r[55] = gi_cell_index(w[42] % 4096u, a.offset, i & 3u);
  return r;
}

// What each result word is; floats carry the absolute difference that counts as equal (at the
// scale of the quantity) besides 4 ulps.
struct Field {
  const char* name;
  int first, size;
  bool is_float;
  double abs_tolerance;
};
const Field kFields[] = {
    {"gi_hemi_direction", 0, 3, true, 6e-8},
    {"gi_hemi_uv", 3, 2, true, 6e-8},
    {"gi_texel_of_local", 5, 1, false, 0},
    {"gi_frame", 6, 9, true, 6e-8},
    {"cell key", 15, 8, false, 0},
    {"cell offset", 23, 2, false, 0},
    {"cell size", 25, 1, true, 0},
    {"bucket/checksum", 26, 4, false, 0},
    {"pcg_hash/gi_xx", 30, 2, false, 0},
    {"gi_hysteresis", 32, 1, true, 6e-8},
    {"gi_cell_update", 33, 4, true, 0},
    {"gi_fixed_split", 37, 2, false, 0},
    {"gi_fixed_value", 39, 1, true, 0},
    {"gi_spawn_jitter", 40, 2, false, 0},
    {"gi_texel_of(texel direction)", 42, 1, false, 0},
    {"gi_texel_direction", 43, 3, true, 6e-8},
    {"gi_sh_basis", 46, 9, true, 6e-8},
    {"gi_cell_index", 55, 1, false, 0},
    {"padding", 56, 8, false, 0},
};

TEST(Gi10MathGpu, MatchesTheCpp) {
  SKIP_WITHOUT_GPU("gi10_math_test");
  const uint32_t count = 1u << 17;
  std::vector<uint32_t> in = make_inputs(count);
  VulkanContext context(0);
  GpuBuffer inputs(context, in.size() * 4), results(context, size_t(count) * kOutWords * 4);
  inputs.upload(std::span<const uint32_t>(in));
  ComputePipeline pipeline(context, "gi10_math_test", 2, 4);
  double ms = pipeline.dispatch({&inputs, &results}, &count, (count + 63) / 64);
  std::vector<uint32_t> out(size_t(count) * kOutWords);
  results.download(std::span<uint32_t>(out));

  std::map<std::string, int64_t> worst_ulps;
  std::map<std::string, double> worst_abs;
  std::map<std::string, int> mismatches;
  for (uint32_t i = 0; i < count; ++i) {
    std::vector<uint32_t> cpu = cpu_outputs(&in[size_t(i) * kInWords], i);
    const uint32_t* gpu = &out[size_t(i) * kOutWords];
    for (const Field& field : kFields) {
      for (int c = field.first; c < field.first + field.size; ++c) {
        if (!field.is_float) {
          if (gpu[c] != cpu[c] && mismatches[field.name]++ < 3)
            ADD_FAILURE() << field.name << " of input " << i << " word " << c << ": GPU " << gpu[c] << ", CPU "
                          << cpu[c];
          continue;
        }
        float g = from_bits(gpu[c]), h = from_bits(cpu[c]);
        int64_t u = ulps(g, h);
        double diff = std::isnan(g) || std::isnan(h) ? (std::isnan(g) && std::isnan(h) ? 0.0 : INFINITY)
                                                     : std::abs(double(g) - h);
        worst_ulps[field.name] = std::max(worst_ulps[field.name], u);
        worst_abs[field.name] = std::max(worst_abs[field.name], diff);
        if (u > 4 && diff > field.abs_tolerance && mismatches[field.name]++ < 3)
          ADD_FAILURE() << field.name << " of input " << i << " word " << c << ": GPU " << g << ", CPU " << h << " ("
                        << u << " ulps)";
      }
    }
  }
  for (const Field& field : kFields) EXPECT_EQ(mismatches[field.name], 0) << field.name;
  std::printf("gi10_math on the GPU, %u inputs in %.1f ms; largest differences from the CPU:\n", count, ms);
  for (const Field& field : kFields)
    if (field.is_float)
      std::printf("  %-30s %lld ulps, %.3g absolute\n", field.name, (long long)worst_ulps[field.name],
                  worst_abs[field.name]);
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
