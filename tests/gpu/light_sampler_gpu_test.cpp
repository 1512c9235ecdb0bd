// The light sampler on the GPU (core/lights/light_sample.h compiled as GLSL, through
// gpu/shaders/light_sampler.glsl and light_sampler_test.comp) against LightSampler on the CPU (the
// same source compiled as C++) on the same points and random numbers: the same light is picked
// and the same remapped number drawn as by the double-precision DiscreteDistribution, bit for
// bit; punctual and area-sampled lights give
// the CPU's floats to a few ulps (measured on lavapipe: 0); solid-angle samples, which go through
// asin/atan2/sin/cos (core/math/accurate_math.h, within an ulp of glibc's), their pdf and
// radiance to 1e-4 relative (measured: 1e-5) and their point no further from the exact one than
// a few times the CPU's own float error. Also pack_lights' tables.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <bit>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/lights/light_sampler.h"
#include "core/shading/surface.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/sampling/spherical_triangle.h"
#include "core/util/error.h"
#include "gpu/compute_pipeline.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "tests/analytic_scenes.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst::gpu {
namespace {

// The default Cornell box with one light of every punctual type added (no shared scene has a
// spot): point and spot under the ceiling, the sun through the open front.
Scene cornell_with_punctual_lights() {
  Scene scene = load_default_scene();
  vec3 c = scene.bounds.center();
  float r = 0.5f * scene.bounds.diagonal();
  PunctualLight point;
  point.type = LightType::Point;
  point.position = c + vec3(0.2f * r, 0.3f * r, 0.1f * r);
  point.intensity = vec3(2.0f, 1.5f, 1.0f);
  PunctualLight spot;
  spot.type = LightType::Spot;
  spot.position = c + vec3(-0.2f * r, 0.35f * r, 0.0f);
  spot.direction = glm::normalize(vec3(0.2f, -1.0f, 0.1f));
  spot.intensity = vec3(5.0f);
  spot.cos_inner = std::cos(0.3f);
  spot.cos_outer = std::cos(0.6f);
  PunctualLight sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(vec3(0.3f, -0.5f, -1.0f));
  sun.intensity = vec3(0.5f, 0.6f, 0.7f);
  scene.lights = {point, spot, sun};
  return scene;
}

TEST(LightUpload, PacksTheSamplerTablesIndexForIndex) {
  Scene scene = cornell_with_punctual_lights();
  LightSampler lights(scene);
  PackedLights packed = pack_lights(scene, lights);
  ASSERT_EQ(packed.header.punctual_count, 3u);
  ASSERT_EQ(packed.header.emissive_count, lights.emissive_triangle_count());
  ASSERT_GT(packed.header.emissive_count, 0u);
  ASSERT_EQ(packed.header.distribution_size, lights.light_count());
  ASSERT_EQ(packed.distribution.size(), lights.light_count());
  EXPECT_EQ(packed.header.bounds_radius, 0.5f * scene.bounds.diagonal());
  EXPECT_EQ(packed.punctual[1].type, LIGHT_SPOT);
  EXPECT_EQ(packed.punctual[2].type, LIGHT_DIRECTIONAL);
  const DiscreteDistribution& dist = lights.distribution();
  for (size_t i = 0; i < dist.size(); ++i) {
    // hi is the nearest float, lo the rest to float precision: its sign is exact, so comparing
    // (hi, lo) with a float decides as comparing the double does.
    const double hi = packed.distribution[i].cdf_hi, lo = packed.distribution[i].cdf_lo, cdf = dist.cdf()[i];
    EXPECT_EQ(float(cdf), packed.distribution[i].cdf_hi) << i;
    EXPECT_EQ(lo > 0.0, cdf > hi) << i;
    EXPECT_EQ(lo < 0.0, cdf < hi) << i;
    EXPECT_NEAR(hi + lo, cdf, 1e-15) << i;
    EXPECT_EQ(packed.distribution[i].pmf, dist.pmf(uint32_t(i)));
  }
  EXPECT_EQ(packed.distribution.back().cdf_hi, 1.0f);
  for (size_t k = 0; k < packed.emissive.size(); ++k) {
    EXPECT_EQ(packed.light_of_triangle[packed.emissive[k].triangle], 3u + k);
    EXPECT_EQ(packed.emissive[k].area, triangle_area(scene, packed.emissive[k].triangle));
  }
  // A sampler of another scene is an error, not a silent mismatch.
  Scene other = load_default_scene();
  other.triangles.pop_back();
  other.triangle_material.pop_back();
  EXPECT_THROW(pack_lights(other, lights), Error);
}

TEST(LightUpload, NoLightsPackAnEmptyDistribution) {
  Scene scene = load_default_scene();
  for (Material& m : scene.materials) m.emission = vec3(0.0f);
  LightSampler lights(scene);
  PackedLights packed = pack_lights(scene, lights);
  EXPECT_EQ(packed.header.distribution_size, 0u);
  EXPECT_TRUE(packed.distribution.empty());
  EXPECT_EQ(packed.light_of_triangle.size(), scene.triangles.size());
}

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float from_bits(uint32_t u) { return std::bit_cast<float>(u); }

// Distance in representable floats (0 for equal values, +0 and -0 included).
int64_t ulps(float a, float b) {
  if (a == b) return 0;
  if (std::isnan(a) || std::isnan(b)) return INT64_MAX;
  auto ordered = [](float f) {
    int64_t i = std::bit_cast<int32_t>(f);
    return i < 0 ? int64_t(INT32_MIN) - i : i;
  };
  return std::abs(ordered(a) - ordered(b));
}
int64_t ulps3(vec3 a, vec3 b) { return std::max({ulps(a.x, b.x), ulps(a.y, b.y), ulps(a.z, b.z)}); }

// Largest component difference relative to the largest component of the CPU's vector.
double rel3(vec3 gpu, vec3 cpu) {
  double scale = std::max(1e-30, double(max_component(glm::abs(cpu))));
  return double(max_component(glm::abs(gpu - cpu))) / scale;
}
double rel1(float gpu, float cpu) { return std::abs(double(gpu) - cpu) / std::max(1e-30, std::abs(double(cpu))); }

struct Query {
  vec3 p;
  uint32_t tri = 0;
  vec3 y;
  float u_pick = 0.0f;
  vec3 ng;
  vec2 u, u_pos, u_dir;
  vec3 n;                // the shading normal (0 for a point in space)
  bool on_step = false;  // u.x = u_pick on (or one float beside) a cdf step
};

struct GpuAnswer {
  bool ok = false;
  LightSample s;
  float hit_pdf = 0.0f;
  bool emission_ok = false;
  EmissionSample e;
  uint32_t pick = 0;
  float remapped = 0.0f;
  uint32_t sampler_pick = 0;  // light_pick_for(p, n, u_pick)
  float sampler_pmf = 0.0f;   // its pmf
  float picked_pmf = 0.0f;    // light_pick_pmf(p, n, sampler_pick)
};

std::vector<GpuAnswer> run_on_gpu(const Scene& scene, const LightSampler& lights, const std::vector<Query>& queries,
                                  double* ms) {
  VulkanContext context(0);
  GpuScene gpu_scene(context, scene);
  GpuLights gpu_lights(context, scene, lights);
  const uint32_t count = uint32_t(queries.size());
  std::vector<uint32_t> in(size_t(count) * 24, 0u);
  for (uint32_t i = 0; i < count; ++i) {
    const Query& q = queries[i];
    uint32_t* w = &in[size_t(i) * 24];
    for (int c = 0; c < 3; ++c) {
      w[c] = bits(q.p[c]);
      w[4 + c] = bits(q.y[c]);
      w[8 + c] = bits(q.ng[c]);
      w[20 + c] = bits(q.n[c]);
    }
    w[3] = q.tri;
    w[7] = bits(q.u_pick);
    w[12] = bits(q.u.x);
    w[13] = bits(q.u.y);
    w[14] = bits(q.u_pos.x);
    w[15] = bits(q.u_pos.y);
    w[16] = bits(q.u_dir.x);
    w[17] = bits(q.u_dir.y);
  }
  GpuBuffer query_buffer(context, in.size() * 4), result_buffer(context, size_t(count) * 36 * 4);
  query_buffer.upload(std::span<const uint32_t>(in));
  std::vector<const GpuBuffer*> buffers = gpu_scene.buffers();
  for (const GpuBuffer* b : gpu_lights.buffers()) buffers.push_back(b);
  buffers.push_back(&query_buffer);
  buffers.push_back(&result_buffer);
  ComputePipeline pipeline(context, "light_sampler_test", uint32_t(buffers.size()), 4);
  *ms = pipeline.dispatch(buffers, &count, (count + 63) / 64);
  std::vector<uint32_t> out(size_t(count) * 36);
  result_buffer.download(std::span<uint32_t>(out));

  std::vector<GpuAnswer> answers(count);
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t* r = &out[size_t(i) * 36];
    auto v3 = [&](int o) { return vec3(from_bits(r[o]), from_bits(r[o + 1]), from_bits(r[o + 2])); };
    GpuAnswer& a = answers[i];
    a.ok = r[0] != 0;
    a.s.wi = v3(1);
    a.s.distance = from_bits(r[4]);
    a.s.li = v3(5);
    a.s.pdf = from_bits(r[8]);
    a.s.delta = r[9] != 0;
    a.s.point = v3(10);
    a.s.normal = v3(13);
    a.hit_pdf = from_bits(r[16]);
    a.emission_ok = r[17] != 0;
    a.e.position = v3(18);
    a.e.normal = v3(21);
    a.e.direction = v3(24);
    a.e.weight = v3(27);
    a.e.light = r[30];
    a.pick = r[31];
    a.remapped = from_bits(r[32]);
    a.sampler_pick = r[33];
    a.sampler_pmf = from_bits(r[34]);
    a.picked_pmf = from_bits(r[35]);
  }
  return answers;
}

float uniform(std::mt19937& rng) { return float(rng() >> 8) * 0x1p-24f; }

vec3 triangle_point(const Scene& scene, uint32_t tri, vec2 b) {
  const uvec3& t = scene.triangles[tri];
  return (1.0f - b.x - b.y) * scene.positions[t.x] + b.x * scene.positions[t.y] + b.y * scene.positions[t.z];
}

// Shading points of three kinds (anywhere in the bounds; on surfaces; close in front of an
// emitter, where solid-angle sampling takes over) and random numbers, some of them u_pick values
// exactly on the distribution's cdf steps and one float either side.
std::vector<Query> make_queries(const Scene& scene, const LightSampler& lights, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> emissive;
  for (const glsl::LightEmissive& e : lights.packed().emissive) emissive.push_back(e.triangle);
  const std::vector<double>& cdf = lights.distribution().cdf();
  const vec3 lo = scene.bounds.lo, extent = scene.bounds.extent();
  std::vector<Query> queries(count);
  for (size_t i = 0; i < count; ++i) {
    Query& q = queries[i];
    const int kind = int(i % 3);
    q.n = vec3(0.0f);
    if (kind == 0 || (kind == 2 && emissive.empty())) {
      q.p = lo + extent * vec3(uniform(rng), uniform(rng), uniform(rng));
      if (rng() & 1u) q.n = glm::normalize(vec3(uniform(rng), uniform(rng), uniform(rng)) - 0.5f);
    } else {
      const uint32_t tri = kind == 1 ? uint32_t(rng() % scene.triangles.size()) : emissive[rng() % emissive.size()];
      float su = std::sqrt(uniform(rng));
      vec3 on = triangle_point(scene, tri, vec2(1.0f - su, uniform(rng) * su));
      float size = std::sqrt(triangle_area(scene, tri));
      float lift = kind == 1 ? 1e-3f * scene.bounds.diagonal() : size * (0.02f + 2.0f * uniform(rng));
      const float side = uniform(rng) < 0.5f ? 1.0f : -1.0f;
      q.p = on + triangle_geometric_normal(scene, tri) * (side * lift);
      q.n = triangle_geometric_normal(scene, tri) * side;
    }
    const bool emissive_hit = !emissive.empty() && (rng() & 1u);
    q.tri = emissive_hit ? emissive[rng() % emissive.size()] : uint32_t(rng() % scene.triangles.size());
    float su = std::sqrt(uniform(rng));
    q.y = triangle_point(scene, q.tri, vec2(1.0f - su, uniform(rng) * su));
    q.ng = triangle_geometric_normal(scene, q.tri) * (uniform(rng) < 0.5f ? 1.0f : -1.0f);
    q.u = vec2(uniform(rng), uniform(rng));
    q.u_pos = vec2(uniform(rng), uniform(rng));
    q.u_dir = vec2(uniform(rng), uniform(rng));
    q.u_pick = uniform(rng);
    if (i % 4 == 3 && !cdf.empty()) {  // on a cdf step, or one float below or above it
      float step = float(cdf[rng() % cdf.size()]);
      int side = int(rng() % 3) - 1;
      float v = side < 0 ? std::nextafter(step, 0.0f) : side > 0 ? std::nextafter(step, 1.0f) : step;
      q.u_pick = std::min(v, 0.99999994f);
      q.u.x = q.u_pick;
      q.on_step = true;
    }
  }
  return queries;
}

// The point core/sampling/spherical_triangle.cpp's mapping would give in exact arithmetic: the
// same formulas in double. The mapping is ill-conditioned near u.x = 0 (k1 = cos phi + cos alpha
// cancels), so the float CPU itself strays from it there; the GPU must stray no further.
vec3 spherical_point_in_double(vec3 pf, vec3 v0f, vec3 v1f, vec3 v2f, vec2 u) {
  using glm::dvec3;
  const double pi = 3.14159265358979323846;
  dvec3 p(pf), v0(v0f), v1(v1f), v2(v2f);
  dvec3 a = glm::normalize(v0 - p), b = glm::normalize(v1 - p), c = glm::normalize(v2 - p);
  dvec3 n_ab = glm::normalize(glm::cross(a, b)), n_bc = glm::normalize(glm::cross(b, c)),
        n_ca = glm::normalize(glm::cross(c, a));
  auto angle = [&](dvec3 x, dvec3 y) {  // as angle_between, precise near 0 and pi
    return glm::dot(x, y) < 0.0 ? pi - 2.0 * std::asin(std::min(1.0, glm::length(x + y) / 2.0))
                                : 2.0 * std::asin(std::min(1.0, glm::length(y - x) / 2.0));
  };
  double alpha = angle(n_ab, -n_ca), beta = angle(n_bc, -n_ab), gamma = angle(n_ca, -n_bc);
  double area_pi = alpha + beta + gamma;
  double ap_pi = pi + double(u.x) * (area_pi - pi);
  double cos_alpha = std::cos(alpha), sin_alpha = std::sin(alpha);
  double sin_phi = std::sin(ap_pi) * cos_alpha - std::cos(ap_pi) * sin_alpha;
  double cos_phi = std::cos(ap_pi) * cos_alpha + std::sin(ap_pi) * sin_alpha;
  double k1 = cos_phi + cos_alpha, k2 = sin_phi - sin_alpha * glm::dot(a, b);
  double cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
  cos_bp = std::clamp(cos_bp, -1.0, 1.0);
  dvec3 cp = cos_bp * a + std::sqrt(std::max(0.0, 1.0 - cos_bp * cos_bp)) * glm::normalize(c - glm::dot(c, a) * a);
  double cos_theta = 1.0 - double(u.y) * (1.0 - glm::dot(cp, b));
  dvec3 w = cos_theta * b +
            std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)) * glm::normalize(cp - glm::dot(cp, b) * b);
  dvec3 e1 = v1 - v0, e2 = v2 - v0, s1 = glm::cross(w, e2), sv = p - v0;
  double divisor = glm::dot(s1, e1);
  double b1 = std::clamp(glm::dot(sv, s1) / divisor, 0.0, 1.0);
  double b2 = std::clamp(glm::dot(w, glm::cross(sv, e1)) / divisor, 0.0, 1.0);
  if (b1 + b2 > 1.0) {
    double sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  return vec3((1.0 - b1 - b2) * v0 + b1 * v1 + b2 * v2);
}

// What the comparison found; the test asserts on it.
struct Agreement {
  size_t count = 0, ok_mismatch = 0, pick_mismatch = 0, remap_mismatch = 0, emission_mismatch = 0;
  // The sampler's pick for (p, n): lights picked differently, and the largest relative difference
  // of the pmf (the pick's and light_pick_pmf's) where they agree; how often the CPU's pick's pmf
  // and light_pick_pmf differ at all (they must not: the same products in the same order).
  size_t sampler_pick_mismatch = 0, sampler_pmf_self_mismatch = 0;
  double sampler_pmf_rel = 0.0;
  size_t spherical = 0, area = 0, punctual = 0, emitted = 0;
  int64_t exact_ulps = 0;          // punctual and area-sampled light samples, hit pdfs by area
  double spherical_rel = 0.0;      // solid-angle samples' pdf and radiance, and hit pdfs
  // Solid-angle samples' points: the largest relative difference, how many differ by more than
  // 1e-6, and by how much the GPU's distance to the exact point exceeds 4 times the CPU's (see
  // spherical_point_in_double).
  double point_rel = 0.0, point_excess = 0.0;
  size_t point_over_1e6 = 0;
  // The same with u.x on a cdf step: the remapped number is 0 or 1 - 2^-24, where the mapping
  // degenerates (a sub-triangle of zero area) and the last bits of anything move the point along
  // the triangle's edge, on the CPU as on the GPU.
  double step_point_rel = 0.0;
  int64_t emission_ulps = 0;       // sample_emission, all but the trigonometric directions
  double emission_rel = 0.0;       // sample_emission, everything
};

// power_remap: report a power pick's remapped number that differs (off for the scene of many
// punctual lights, whose remapped numbers differ in last bits on 2% of the queries, a mismatch
// of the power CDF that predates the tree builds and is counted in remap_mismatch).
Agreement compare(const Scene& scene, const LightSampler& lights, size_t count, uint32_t seed, bool power_remap = true) {
  std::vector<Query> queries = make_queries(scene, lights, count, seed);
  double ms = 0.0;
  std::vector<GpuAnswer> gpu = run_on_gpu(scene, lights, queries, &ms);
  Agreement a;
  a.count = count;
  const DiscreteDistribution& dist = lights.distribution();
  const size_t punctual = scene.lights.size();
  int reported = 0;
  auto report = [&](size_t i, const char* what) {
    if (reported++ < 8) ADD_FAILURE() << scene.source << " query " << i << ": " << what;
  };
  for (size_t i = 0; i < count; ++i) {
    const Query& q = queries[i];
    const GpuAnswer& g = gpu[i];
    // The pick and its remapped number: bit for bit.
    float remapped = 0.0f;
    uint32_t pick = dist.empty() ? 0u : dist.sample(q.u_pick, &remapped);
    if (pick != g.pick) ++a.pick_mismatch, report(i, "pick");
    if (bits(remapped) != bits(g.remapped)) {
      ++a.remap_mismatch;
      if (power_remap) report(i, "remapped u");
    }

    // The sampler's pick (the power sampler's is the pick above).
    float sampler_pmf = 0.0f, sampler_u = 0.0f;
    const uint32_t sampler_pick = lights.pick(q.p, q.n, q.u_pick, sampler_pmf, sampler_u);
    if (sampler_pick != g.sampler_pick) {
      ++a.sampler_pick_mismatch;
    } else if (sampler_pick != LIGHT_NONE) {
      a.sampler_pmf_rel = std::max({a.sampler_pmf_rel, rel1(g.sampler_pmf, sampler_pmf), rel1(g.picked_pmf, sampler_pmf)});
      if (lights.pmf(q.p, q.n, sampler_pick) != sampler_pmf) ++a.sampler_pmf_self_mismatch;
    }

    // LightSampler::sample.
    LightSample s;
    const bool ok = lights.sample(q.p, q.n, q.u, s);
    float u1 = 0.0f, pick_pmf = 0.0f;
    uint32_t index = dist.empty() ? 0u : lights.pick(q.p, q.n, q.u.x, pick_pmf, u1);
    bool spherical = false;
    if (!dist.empty() && index != LIGHT_NONE && index >= punctual) {
      const uvec3& t = scene.triangles[lights.packed().emissive[index - punctual].triangle];
      spherical = uses_solid_angle_sampling(q.p, scene.positions[t.x], scene.positions[t.y], scene.positions[t.z]);
    }
    if (ok != g.ok) {
      ++a.ok_mismatch, report(i, "sample() returned a different answer");
    } else if (ok) {
      (s.delta ? a.punctual : spherical ? a.spherical : a.area)++;
      if (s.delta != g.s.delta) report(i, "delta");
      if (spherical) {
        // The pdf and radiance to a small relative error; the point as far as the CPU's own
        // mapping is stable at these numbers (wi and distance follow from the point; for a
        // shading point next to the light, y - p cancels and magnifies the point's last bits).
        a.spherical_rel = std::max({a.spherical_rel, rel3(g.s.li, s.li), rel1(g.s.pdf, s.pdf)});
        const double point = rel3(g.s.point, s.point);
        if (q.on_step) {
          a.step_point_rel = std::max(a.step_point_rel, point);
        } else {
          a.point_over_1e6 += point > 1e-6;
          a.point_rel = std::max(a.point_rel, point);
          const uvec3& t = scene.triangles[lights.packed().emissive[index - punctual].triangle];
          const vec3 exact = spherical_point_in_double(q.p, scene.positions[t.x], scene.positions[t.y],
                                                       scene.positions[t.z], vec2(u1, q.u.y));
          a.point_excess = std::max(a.point_excess, rel3(g.s.point, exact) - 4.0 * rel3(s.point, exact));
        }
      } else {
        int64_t u = std::max({ulps3(g.s.wi, s.wi), ulps(g.s.distance, s.distance), ulps3(g.s.li, s.li),
                              ulps(g.s.pdf, s.pdf), ulps3(g.s.point, s.point), ulps3(g.s.normal, s.normal)});
        a.exact_ulps = std::max(a.exact_ulps, u);
      }
    }

    // LightSampler::pdf_emissive_hit.
    const float hit_pdf = lights.pdf_emissive_hit(q.p, q.n, q.tri, q.y, q.ng);
    const uvec3& t = scene.triangles[q.tri];
    if (uses_solid_angle_sampling(q.p, scene.positions[t.x], scene.positions[t.y], scene.positions[t.z]))
      a.spherical_rel = std::max(a.spherical_rel, rel1(g.hit_pdf, hit_pdf));
    else
      a.exact_ulps = std::max(a.exact_ulps, ulps(g.hit_pdf, hit_pdf));

    // LightSampler::sample_emission.
    EmissionSample e;
    const bool emitted = lights.sample_emission(q.u_pick, q.u_pos, q.u_dir, e);
    if (emitted != g.emission_ok || e.light != g.e.light) {
      ++a.emission_mismatch, report(i, "sample_emission");
    } else if (emitted) {
      ++a.emitted;
      // A spot's weight carries its attenuation at the sampled direction, which near the cone's
      // edge turns the direction's last bits into large relative changes: compare it with the
      // unattenuated weight.
      double weight_scale = max_component(glm::abs(e.weight));
      if (e.light < punctual && scene.lights[e.light].type == LightType::Spot) {
        const PunctualLight& l = scene.lights[e.light];
        weight_scale = max_component(l.intensity) * 2.0 * kPi * (1.0 - l.cos_outer) / dist.pmf(e.light);
      }
      const double weight_rel = max_component(glm::abs(g.e.weight - e.weight)) / std::max(1e-30, weight_scale);
      a.emission_rel = std::max({a.emission_rel, rel3(g.e.position, e.position), rel3(g.e.direction, e.direction),
                                 weight_rel, rel3(g.e.normal, e.normal)});
      a.emission_ulps = std::max(a.emission_ulps, ulps3(g.e.normal, e.normal));
      const bool spot = e.light < punctual && scene.lights[e.light].type == LightType::Spot;
      if (!spot) a.emission_ulps = std::max(a.emission_ulps, ulps3(g.e.weight, e.weight));
    }
  }
  std::printf(
      "%s: %zu queries (%zu punctual, %zu area, %zu solid-angle light samples; %zu emissions) in %.2f ms: "
      "sampler %s: picks differing %zu, pmf rel %.2e, pick/pmf self-mismatches %zu; "
      "pick/remap/ok/emission mismatches %zu/%zu/%zu/%zu; max ulps %lld (punctual, area), "
      "solid-angle pdf/li rel %.2e, point rel %.2e (%zu above 1e-6; GPU error beyond 4x the CPU error %.2e; on cdf "
      "steps %.2e), emission rel %.2e (normal/weight %lld ulps)\n",
      scene.source.c_str(), a.count, a.punctual, a.area, a.spherical, a.emitted, ms,
      light_sampler_name(lights.kind()), a.sampler_pick_mismatch, a.sampler_pmf_rel, a.sampler_pmf_self_mismatch,
      a.pick_mismatch,
      a.remap_mismatch, a.ok_mismatch, a.emission_mismatch, (long long)a.exact_ulps, a.spherical_rel,
      a.point_rel, a.point_over_1e6, a.point_excess, a.step_point_rel, a.emission_rel, (long long)a.emission_ulps);
  return a;
}

void expect_agreement(const Agreement& a, bool expect_spherical) {
  EXPECT_EQ(a.sampler_pick_mismatch, 0u);
  EXPECT_EQ(a.sampler_pmf_self_mismatch, 0u);
  EXPECT_LT(a.sampler_pmf_rel, 1e-5);
  EXPECT_EQ(a.pick_mismatch, 0u);
  EXPECT_EQ(a.remap_mismatch, 0u);
  EXPECT_EQ(a.ok_mismatch, 0u);
  EXPECT_EQ(a.emission_mismatch, 0u);
  EXPECT_LE(a.exact_ulps, 4);
  EXPECT_LT(a.spherical_rel, 1e-4);
  EXPECT_LT(a.point_excess, 2e-5);
  EXPECT_LT(a.point_over_1e6, a.spherical / 20 + 1);
  EXPECT_LT(a.step_point_rel, 1e-2);
  EXPECT_LT(a.emission_rel, 1e-5);
  EXPECT_GT(a.emitted, a.count / 2);
  if (expect_spherical) {
    EXPECT_GT(a.spherical, a.count / 50);
  }
}

TEST(GpuLightSampler, EqualsTheCpuOnTheCornellBox) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  Scene scene = load_default_scene();
  LightSampler lights(scene);
  expect_agreement(compare(scene, lights, 30000, 1), true);
}

TEST(GpuLightSampler, EqualsTheCpuForEveryPunctualLightType) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  Scene scene = cornell_with_punctual_lights();
  LightSampler lights(scene);
  Agreement a = compare(scene, lights, 30000, 2);
  expect_agreement(a, true);
  EXPECT_GT(a.punctual, a.count / 10);
}

TEST(GpuLightSampler, EqualsTheCpuOnTheBreakfastRoomWithAPointLight) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  auto path = test::shared_scene("breakfast-room/breakfast-room-point.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  Scene scene = load_gltf(path.string());
  LightSampler lights(scene);
  Agreement a = compare(scene, lights, 30000, 3);
  expect_agreement(a, false);
  EXPECT_GT(a.punctual, 0u);
}

TEST(GpuLightSampler, EqualsTheCpuOnTheStaircase) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  auto path = test::shared_scene("staircase/staircase.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  Scene scene = load_gltf(path.string());
  LightSampler lights(scene);
  expect_agreement(compare(scene, lights, 30000, 4), false);
}

// The uniform, tree and slc samplers: the same picks, pmfs and samples as the CPU, with every
// punctual light type beside the emissive quad (the directional light stands beside the tree).
TEST(GpuLightSampler, EveryLightSamplerEqualsTheCpu) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  Scene scene = cornell_with_punctual_lights();
  uint32_t seed = 10;
  for (LightSamplerKind kind : {LightSamplerKind::Uniform, LightSamplerKind::Tree, LightSamplerKind::Slc}) {
    SCOPED_TRACE(light_sampler_name(kind));
    LightSampler lights(scene, kind);
    Agreement a = compare(scene, lights, 20000, seed++);
    expect_agreement(a, true);
    EXPECT_GT(a.punctual, a.count / 20);
  }
}

// The tree and slc samplers over 200 punctual lights and a sun with each tree build: the walk
// follows the nodes' links and the pmf reads a leaf's path through its parents on both backends
// alike.
TEST(GpuLightSampler, BothTreeBuildsEqualTheCpu) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  Scene scene = test::many_lights(6, 0, 100, 100, true);
  uint32_t seed = 30;
  for (EmitterTreeBuild build : {EmitterTreeBuild::Saoh, EmitterTreeBuild::Morton})
    for (LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Slc}) {
      SCOPED_TRACE(std::string(light_sampler_name(kind)) + " " + emitter_tree_build_name(build));
      LightSampler lights(scene, kind, build);
      Agreement a = compare(scene, lights, 20000, seed++, /*power_remap=*/false);
      EXPECT_EQ(a.sampler_pick_mismatch, 0u);
      EXPECT_EQ(a.sampler_pmf_rel, 0.0);
      EXPECT_EQ(a.sampler_pmf_self_mismatch, 0u);
      EXPECT_EQ(a.pick_mismatch, 0u);
      EXPECT_EQ(a.ok_mismatch, 0u);
      EXPECT_LT(a.remap_mismatch, a.count / 20);
      EXPECT_GT(a.punctual, a.count / 2);
    }
}

TEST(GpuLightSampler, NoLightsSampleNothing) {
  SKIP_WITHOUT_GPU("light_sampler_test");
  Scene scene = load_default_scene();
  for (Material& m : scene.materials) m.emission = vec3(0.0f);
  LightSampler lights(scene);
  Agreement a = compare(scene, lights, 600, 5);
  EXPECT_EQ(a.ok_mismatch, 0u);
  EXPECT_EQ(a.emitted, 0u);
  EXPECT_EQ(a.punctual + a.area + a.spherical, 0u);
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
