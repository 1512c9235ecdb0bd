// The contribution of one VPL, and exhaustive VPL shading against the path tracer.
#include "core/vpl/vpl_shading.h"

#include <gtest/gtest.h>

#include "core/pt/path_tracer.h"
#include "core/shading/surface.h"
#include "core/vpl/vpl_generator.h"
#include "tests/analytic_scenes.h"
#include "tests/core/vpl/vpl_test_util.h"

namespace sst {
namespace {

using test::mean_error;
using test::PreparedScene;

Vpl vpl_at(vec3 p, vec3 n, vec3 intensity) {
  Vpl v;
  v.position = p;
  v.normal = glm::normalize(n);
  v.intensity = intensity;
  return v;
}

// A VPL facing a plane: E = I cos_j cos_x / d^2, both cosines measured along the connecting line.
TEST(VplShading, IrradianceIsIntensityTimesBothCosinesOverDistanceSquared) {
  const Vpl v = vpl_at({0.3f, -0.2f, 1.5f}, {0.2f, 0.1f, -1.0f}, vec3(2.0f, 1.0f, 0.5f));
  const vec3 n(0, 0, 1);
  for (vec3 x : {vec3(0), vec3(1, 1, 0), vec3(-2, 0.5f, 0), vec3(3, -3, 0)}) {
    vec3 d = v.position - x;
    float dist = glm::length(d);
    float cos_x = d.z / dist, cos_j = glm::dot(v.normal, -d / dist);
    vec3 expected = v.intensity * std::max(cos_j, 0.0f) * cos_x / (dist * dist);
    vec3 got = vpl_irradiance(v, x, n, n, 1e-3f);
    EXPECT_NEAR(got.x, expected.x, 1e-5f * expected.x + 1e-9f);
    EXPECT_NEAR(got.z, expected.z, 1e-5f * expected.z + 1e-9f);
    // Lambert: radiance = albedo / pi * E whatever wo.
    Brdf lambert = brdf_from_material(vec3(0.6f), 0.0f, 1.0f, true);
    Basis basis = basis_from_normal(n);
    vec3 l = vpl_contribution(v, x, n, basis, lambert, glm::normalize(vec3(0.3f, 0.1f, 1.0f)), 1e-3f);
    EXPECT_NEAR(l.x, 0.6f / kPi * expected.x, 1e-5f * expected.x + 1e-9f);
  }
}

TEST(VplShading, ClampBoundsTheInverseSquare) {
  const Vpl v = vpl_at({0, 0, 0.01f}, {0, 0, -1}, vec3(1.0f));
  const vec3 n(0, 0, 1);
  EXPECT_NEAR(vpl_irradiance(v, vec3(0), n, n, 0.1f).x, 1.0f / 0.01f, 1e-3f);            // 1/c^2
  EXPECT_NEAR(vpl_irradiance(v, vec3(0), n, n, 0.001f).x, 1.0f / (0.01f * 0.01f), 1.0f);  // 1/d^2
}

TEST(VplShading, BackFacingAndCoincidentVplsGiveZero) {
  const vec3 n(0, 0, 1);
  // VPL facing away from x; x facing away from the VPL; VPL below the surface; same point.
  EXPECT_EQ(vpl_irradiance(vpl_at({0, 0, 1}, {0, 0, 1}, vec3(1)), vec3(0), n, n, 0.01f).x, 0.0f);
  EXPECT_EQ(vpl_irradiance(vpl_at({0, 0, 1}, {0, 0, -1}, vec3(1)), vec3(0), -n, -n, 0.01f).x, 0.0f);
  EXPECT_EQ(vpl_irradiance(vpl_at({0, 0, -1}, {0, 0, 1}, vec3(1)), vec3(0), n, n, 0.01f).x, 0.0f);
  vec3 e = vpl_irradiance(vpl_at({0, 0, 0}, {0, 0, 1}, vec3(1)), vec3(0), n, n, 0.0f);
  EXPECT_TRUE(is_finite(e));
  EXPECT_EQ(e.x, 0.0f);
  // A bent shading normal does not let light through the geometric surface.
  vec3 bent = glm::normalize(vec3(1, 0, 0.2f));
  EXPECT_EQ(vpl_irradiance(vpl_at({1, 0, -0.1f}, {-1, 0, 0}, vec3(1)), vec3(0), bent, n, 0.01f).x, 0.0f);
}

// Exhaustive VPL shading (every VPL, with visibility) reproduces the path tracer's indirect light
// in a closed box lit by a point light, for one bounce and for three. Both estimates are
// Monte Carlo: the tolerance combines their measured standard errors.
class VplExhaustive : public ::testing::TestWithParam<int> {};

TEST_P(VplExhaustive, MatchesThePathTracersIndirectLight) {
  const int bounces = GetParam();
  const float albedo = 0.5f;
  Scene scene = test::diffuse_box(vec3(albedo), 2.0f);
  scene.lights.push_back(test::punctual_light(LightType::Point, {0.3f, 0.5f, -0.2f}, {0, 0, -1}, vec3(1.0f)));
  PreparedScene p(std::move(scene));
  RenderOptions options;
  options.diffuse_only = true;
  PinholeCamera camera(p.scene.cameras[0], 8, 8);
  RenderContext context{p.scene, *p.accel, *p.lights, camera, options, 8, 8, true};

  VplParams vp;
  vp.vpls = 60000 * bounces;
  vp.vpl_max_bounces = bounces;
  vp.vpl_min_bounces = 100;  // no roulette: every path deposits exactly `bounces` VPLs
  VplStats stats;
  VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, vp, 21, true, &stats);
  ASSERT_EQ(vpls.size(), stats.paths * size_t(bounces));
  const float clamp = 1e-4f * p.scene.bounds.diagonal();  // far below any wall-to-point distance used

  PathTracerParams pt;
  pt.max_bounces = bounces;
  pt.rr_min_bounces = 100;
  const vec3 targets[] = {{0.2f, -1.0f, 0.3f}, {1.0f, 0.4f, -0.5f}, {-0.5f, 1.0f, 0.1f}};
  for (uint32_t t = 0; t < 3; ++t) {
    Ray ray;
    ray.origin = vec3(0.0f);
    ray.direction = glm::normalize(targets[t]);
    Hit hit = p.accel->intersect(ray);
    ASSERT_TRUE(hit.valid());
    Surface s = make_surface(p.scene, hit, ray.direction);
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, true);
    Basis basis = basis_from_normal(s.ns);
    vec3 wo = to_local(basis, -ray.direction);

    // One estimate per light path: P times the sum over its VPLs.
    std::vector<double> per_path(stats.paths, 0.0);
    for (size_t j = 0; j < vpls.size(); ++j) {
      vec3 c = vpl_contribution(vpls[j], s.p, s.ng, basis, brdf, wo, clamp);
      if (c.x > 0.0f && p.accel->occluded(vpl_shadow_ray(*p.accel, s.p, s.ng, vpls[j]))) c = vec3(0.0f);
      per_path[j / size_t(bounces)] += double(c.x) * double(stats.paths);
    }
    auto vpl = mean_error(per_path);

    std::vector<double> samples;
    for (uint32_t i = 0; i < 200000; ++i) {
      PixelSampler sampler = pixel_sampler(5, t, i);
      RayCounters counters;
      samples.push_back(trace_path(context, pt, ray, sampler, counters).indirect.x);
    }
    auto ref = mean_error(samples);
    double tolerance = 5.0 * std::sqrt(vpl.error * vpl.error + ref.error * ref.error) + 1e-3 * ref.mean;
    EXPECT_NEAR(vpl.mean, ref.mean, tolerance) << "bounces " << bounces << " target " << t;
    EXPECT_GT(ref.mean, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(VplBounces, VplExhaustive, ::testing::Values(1, 3));

}  // namespace
}  // namespace sst
