// The path tracer against analytic scenes whose radiance is known in closed form.
#include "core/pt/path_tracer.h"

#include <gtest/gtest.h>

#include "core/pipeline/renderer.h"
#include "tests/analytic_scenes.h"

namespace sst {
namespace {

// Everything a RenderContext points to, for tracing single rays.
struct Prepared {
  Scene scene;
  RenderOptions options;
  EmbreeAccel accel;
  LightSampler lights;
  PinholeCamera camera;
  RenderContext context;
  explicit Prepared(Scene s)
      : scene(std::move(s)),
        accel(scene),
        lights(scene),
        camera(scene.cameras[0], 8, 8),
        context{scene, accel, lights, camera, options, 8, 8, true} {
    options.diffuse_only = true;
  }
  // Radiance toward the camera at plane point (x, y, 0), seen from straight above.
  vec3 radiance_at(float x, float y, int max_bounces = 0) {
    PathTracerParams params;
    params.max_bounces = max_bounces;
    Ray ray;
    ray.origin = vec3(x, y, 5.0f);
    ray.direction = vec3(0, 0, -1);
    PixelSampler sampler = pixel_sampler(1, 2, 3);
    RayCounters counters;
    PathSample s = trace_path(context, params, ray, sampler, counters);
    return s.direct + s.indirect;
  }
};

PunctualLight light(LightType type, vec3 position, vec3 direction, float intensity) {
  PunctualLight l;
  l.type = type;
  l.position = position;
  l.direction = glm::normalize(direction);
  l.intensity = vec3(intensity);
  return l;
}

TEST(PathTracerAnalytic, PointLightOverLambertPlaneGivesIcosOverD2) {
  const float albedo = 0.6f, intensity = 7.0f;
  const vec3 lp(0.3f, -0.2f, 1.5f);
  Scene scene = test::lambert_plane(albedo, 50.0f, 5.0f, 1.0f);
  scene.lights.push_back(light(LightType::Point, lp, {0, 0, -1}, intensity));
  Prepared p(std::move(scene));
  for (float x : {-3.0f, -0.5f, 0.3f, 1.0f, 4.0f})
    for (float y : {-2.0f, -0.2f, 0.0f, 2.5f}) {
      vec3 d = lp - vec3(x, y, 0);
      float dist = glm::length(d);
      float e = intensity * (d.z / dist) / (dist * dist);  // E = I cos(theta) / d^2
      float expected = albedo / kPi * e;
      vec3 got = p.radiance_at(x, y);
      EXPECT_NEAR(got.x, expected, 0.005f * expected) << "at (" << x << ", " << y << ")";
      EXPECT_EQ(got.x, got.y);
    }
}

TEST(PathTracerAnalytic, DirectionalLightGivesEcos) {
  const float albedo = 0.5f, irradiance = 3.0f;
  const vec3 dir = glm::normalize(vec3(0.4f, 0.2f, -1.0f));  // travelling direction
  Scene scene = test::lambert_plane(albedo, 50.0f, 5.0f, 1.0f);
  scene.lights.push_back(light(LightType::Directional, vec3(0), dir, irradiance));
  Prepared p(std::move(scene));
  float expected = albedo / kPi * irradiance * -dir.z;
  for (float x : {-2.0f, 0.0f, 3.0f}) EXPECT_NEAR(p.radiance_at(x, 1.0f).x, expected, 0.005f * expected);
}

// Vertex normals tilted 73 degrees off the facet: a view under the shading normal but above the
// facet (a coarse curved mesh at a grazing angle) is shaded with the facet's normal instead of
// ending the path; a view above the shading normal still sees the shading normal's cosine.
TEST(PathTracerAnalytic, ViewUnderTheShadingNormalIsShadedWithTheFacetNormal) {
  const float albedo = 0.5f, irradiance = 3.0f;
  Scene scene = test::lambert_plane(albedo, 50.0f, 5.0f, 1.0f);
  const vec3 tilted = glm::normalize(vec3(1.0f, 0.0f, 0.3f));
  for (vec3& n : scene.normals) n = tilted;
  scene.lights.push_back(light(LightType::Directional, vec3(0), {0, 0, -1}, irradiance));
  Prepared p(std::move(scene));
  auto radiance_along = [&](vec3 travel) {
    PathTracerParams params;
    params.max_bounces = 0;
    Ray ray;
    ray.direction = glm::normalize(travel);
    ray.origin = -5.0f * ray.direction;  // toward the plane's centre
    PixelSampler sampler = pixel_sampler(1, 2, 3);
    RayCounters counters;
    PathSample s = trace_path(p.context, params, ray, sampler, counters);
    return (s.direct + s.indirect).x;
  };
  const float facet = albedo / kPi * irradiance;                  // cos = 1 about the facet's normal
  const float shading = albedo / kPi * irradiance * tilted.z;     // the tilted normal's cosine
  EXPECT_NEAR(radiance_along({1.0f, 0.0f, -0.3f}), facet, 1e-5f * facet);      // under the shading normal
  EXPECT_NEAR(radiance_along({-1.0f, 0.0f, -0.3f}), shading, 1e-5f * shading);  // above it
}

// Hanika's shadow-terminator lift (terminator_lift, core/shading/surface_eval.h) of a triangle
// inscribed in a sphere, with the sphere's normals at its vertices. At the middle of an edge whose
// normals are theta apart, the point is moved onto the two vertices' tangent planes and the two
// averaged: (R/2)(1 - cos theta) along (n0 + n1)/2, from R cos(theta/2) to
// R cos(theta/2) (1 + sin^2(theta/2)) from the centre: outside the sphere by about as much as it
// was inside (the Phong-tessellation overshoot that lifts shadow rays past the terminator).
// Inside the triangle it moves off the facet toward the sphere's side; the vertices, and every
// point of a flat-shaded triangle, stay where they are.
TEST(TerminatorLift, MovesAFacetOntoItsVerticesTangentPlanes) {
  const vec3 centre(0.2f, -0.1f, -3.0f);
  const float radius = 3.5f;
  vec3 v[3], n[3];
  const vec2 at[3] = {{-1.0f, -0.8f}, {1.2f, -0.5f}, {0.1f, 1.1f}};
  for (int i = 0; i < 3; ++i) {
    n[i] = glm::normalize(vec3(at[i].x, at[i].y, 0.0f) - centre);
    v[i] = centre + radius * n[i];
  }
  const vec3 mid = 0.5f * (v[0] + v[1]);
  const vec3 lift = terminator_lift(v[0], v[1], v[2], n[0], n[1], n[2], mid, vec2(0.5f, 0.0f));
  const float cos_theta = glm::dot(n[0], n[1]);
  const vec3 expected = 0.5f * radius * (1.0f - cos_theta) * 0.5f * (n[0] + n[1]);
  EXPECT_LT(glm::length(lift - expected), 1e-5f * radius);
  const float h = 0.5f * std::acos(cos_theta), sin_h = std::sin(h);
  EXPECT_NEAR(glm::length(mid + lift - centre), radius * std::cos(h) * (1.0f + sin_h * sin_h), 1e-5f * radius);
  EXPECT_GT(glm::length(mid + lift - centre), radius);

  const vec3 facet = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
  for (vec2 b : {vec2(1.0f / 3.0f), vec2(0.1f, 0.2f), vec2(0.6f, 0.3f), vec2(0.45f, 0.05f)}) {
    const vec3 p = (1.0f - b.x - b.y) * v[0] + b.x * v[1] + b.y * v[2];
    EXPECT_GT(glm::dot(terminator_lift(v[0], v[1], v[2], n[0], n[1], n[2], p, b), facet), 0.01f);
    EXPECT_LT(glm::length(terminator_lift(v[0], v[1], v[2], facet, facet, facet, p, b)), 1e-6f);
  }
  EXPECT_EQ(terminator_lift(v[0], v[1], v[2], n[0], n[1], n[2], v[0], vec2(0.0f)), vec3(0.0f));
}

// A square facet whose vertex normals lean outward like a dome's, under a directional light just
// below the facet's plane but above the shading normal at the facet's edge toward it: the smooth
// surface sees the light, and the shadow ray from the lifted point decides (no occluder: lit),
// as Cycles' shadow-terminator offset does; with flat normals the same light would leak through
// the surface and stays dark, and light under the shading normal stays dark too.
TEST(PathTracerAnalytic, LightUnderTheFacetButAboveTheSmoothSurfaceReachesIt) {
  const float albedo = 0.5f, irradiance = 2.0f;
  auto scene_with = [&](bool dome, vec3 travel) {
    Scene scene = test::lambert_plane(albedo, 1.0f, 5.0f, 1.0f);
    if (dome)
      for (size_t i = 0; i < scene.normals.size(); ++i) scene.normals[i] = glm::normalize(scene.positions[i] + vec3(0, 0, 2));
    scene.lights.push_back(light(LightType::Directional, vec3(0), travel, irradiance));
    return scene;
  };
  const vec3 toward_plus_x = glm::normalize(vec3(-1.0f, 0.0f, 0.05f));  // travelling: from +x, slightly from below
  Prepared dome(scene_with(true, toward_plus_x));
  const float lit = dome.radiance_at(0.9f, 0.0f).x;
  EXPECT_GT(lit, 0.2f * albedo / kPi * irradiance);
  EXPECT_LT(lit, albedo / kPi * irradiance);
  Prepared flat(scene_with(false, toward_plus_x));
  EXPECT_EQ(flat.radiance_at(0.9f, 0.0f).x, 0.0f);
  EXPECT_EQ(dome.radiance_at(-0.9f, 0.0f).x, 0.0f);  // the far edge's shading normal faces away
}

TEST(PathTracerAnalytic, SpotLightFollowsTheGltfConeFalloff) {
  const float albedo = 0.5f, intensity = 4.0f, h = 2.0f;
  Scene scene = test::lambert_plane(albedo, 50.0f, 5.0f, 1.0f);
  PunctualLight spot = light(LightType::Spot, {0, 0, h}, {0, 0, -1}, intensity);
  spot.cos_inner = std::cos(0.3f);
  spot.cos_outer = std::cos(0.6f);
  scene.lights.push_back(spot);
  Prepared p(std::move(scene));
  for (float angle : {0.0f, 0.2f, 0.35f, 0.45f, 0.55f, 0.7f}) {
    float x = h * std::tan(angle);
    float dist = h / std::cos(angle);
    float cd = std::cos(angle);
    float t = std::clamp((cd - spot.cos_outer) / (spot.cos_inner - spot.cos_outer), 0.0f, 1.0f);
    float expected = albedo / kPi * intensity * t * t * std::cos(angle) / (dist * dist);
    float got = p.radiance_at(x, 0.0f).x;
    EXPECT_NEAR(got, expected, 0.005f * expected + 1e-7f) << "angle " << angle;
  }
}

TEST(PathTracerAnalytic, LightBehindTheSurfaceDoesNotLeakThrough) {
  Scene scene = test::lambert_plane(0.5f, 50.0f, 5.0f, 1.0f);
  scene.lights.push_back(light(LightType::Point, {0, 0, -1}, {0, 0, 1}, 10.0f));
  Prepared p(std::move(scene));
  EXPECT_EQ(p.radiance_at(0.5f, 0.5f).x, 0.0f);
}

// Mean and standard error of the mean over the pixels of an image's first channel.
std::pair<double, double> mean_and_error(const Image& img) {
  double sum = 0, sum2 = 0;
  size_t n = img.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    double v = img.data[i * img.channels];
    sum += v;
    sum2 += v * v;
  }
  double mean = sum / double(n);
  double var = std::max(0.0, sum2 / double(n) - mean * mean);
  return {mean, std::sqrt(var / double(n))};
}

struct FurnaceCase {
  int max_bounces;
  int rr_min_bounces;
};

class PathTracerFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// In a closed box where every surface emits Le and reflects albedo a, the radiance after at most
// N indirect bounces is Le (1 + a + ... + a^(N+1)), whatever the box's shape or size.
TEST_P(PathTracerFurnace, ConvergesToTheGeometricSeries) {
  const float a = 0.5f, le = 1.0f;
  FurnaceCase c = GetParam();
  RenderOptions options;
  options.width = options.height = 24;
  options.spp = 16;
  options.diffuse_only = true;
  options.seed = 7;
  nlohmann::json params = {{"max_bounces", c.max_bounces}, {"rr_min_bounces", c.rr_min_bounces}};
  RenderResult r = render_frame(test::emissive_box(a, le, 2.0f), options, params);
  double expected = le * (1.0 - std::pow(a, c.max_bounces + 2)) / (1.0 - a);
  auto [mean, error] = mean_and_error(r.frame.color);
  // 5 standard errors, measured from this image's pixel variance: fails by chance ~1 in 3.5e6.
  // The floor covers a noiseless estimate (every path fully deterministic).
  EXPECT_NEAR(mean, expected, 5.0 * error + 1e-5 * expected) << "N=" << c.max_bounces;
  EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
}

INSTANTIATE_TEST_SUITE_P(Bounces, PathTracerFurnace,
                         ::testing::Values(FurnaceCase{0, 100}, FurnaceCase{1, 100}, FurnaceCase{3, 100},
                                           FurnaceCase{8, 100}, FurnaceCase{8, 3}, FurnaceCase{40, 2}));

TEST(PathTracerFurnace, DirectLayerHoldsOnlyEmissionAndFirstBounce) {
  const float a = 0.5f, le = 1.0f;
  RenderOptions options;
  options.width = options.height = 16;
  options.spp = 16;
  options.diffuse_only = true;
  RenderResult r = render_frame(test::emissive_box(a, le, 2.0f), options, {{"max_bounces", 4}});
  auto [direct, direct_error] = mean_and_error(r.frame.direct);
  auto [indirect, indirect_error] = mean_and_error(r.frame.indirect);
  EXPECT_NEAR(direct, le * (1.0 + a), 5.0 * direct_error + 1e-5);
  EXPECT_NEAR(indirect, le * (a * a + a * a * a + a * a * a * a + a * a * a * a * a), 5.0 * indirect_error + 1e-5);
}

TEST(PathTracerFurnace, SceneScaleDoesNotChangeTheAnswer) {
  for (float scale : {1e-3f, 1e4f}) {
    Scene scene = test::emissive_box(0.5f, 1.0f, 2.0f);
    test::scale_scene(scene, scale);
    RenderOptions options;
    options.width = options.height = 16;
    options.spp = 8;
    options.diffuse_only = true;
    RenderResult r = render_frame(scene, options, {{"max_bounces", 3}, {"rr_min_bounces", 100}});
    auto [mean, error] = mean_and_error(r.frame.color);
    EXPECT_NEAR(mean, (1.0 - std::pow(0.5, 5)) / 0.5, 5.0 * error + 1e-5) << "scale " << scale;
    EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
  }
}

TEST(PathTracer, SameImageBitsWhateverTheThreadCount) {
  Scene scene = test::emissive_box(0.7f, 1.0f, 2.0f);
  RenderOptions options;
  options.width = 40;
  options.height = 24;
  options.spp = 4;
  options.threads = 1;
  RenderResult one = render_frame(scene, options, {});
  options.threads = 2;
  RenderResult two = render_frame(scene, options, {});
  EXPECT_EQ(one.frame.color.data, two.frame.color.data);
  options.seed = 99;
  RenderResult other_seed = render_frame(scene, options, {});
  EXPECT_NE(one.frame.color.data, other_seed.frame.color.data);
}

TEST(PathTracer, RejectsImpossibleParameters) {
  Scene scene = test::emissive_box(0.5f, 1.0f, 2.0f);
  RenderOptions options;
  options.width = options.height = 4;
  EXPECT_THROW(render_frame(scene, options, {{"max_bounces", -1}}), Error);
  EXPECT_THROW(render_frame(scene, options, {{"max_bounce", 2}}), Error);
  options.spp = 0;
  EXPECT_THROW(render_frame(scene, options, {}), Error);
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// An emissive square of half-size s at height h, facing down, over the Lambert plane.
Scene area_light_over_plane(float albedo, float le, float s, float h, bool double_sided) {
  Scene scene = test::lambert_plane(albedo, 50.0f, 5.0f, 1.0f);
  Material light;
  light.name = "light";
  light.base_color = vec3(0.0f);
  light.metallic = 0.0f;
  light.emission = vec3(le);
  light.double_sided = double_sided;
  scene.materials.push_back(light);
  uint32_t base = uint32_t(scene.positions.size());
  for (vec3 p : {vec3(-s, -s, h), vec3(-s, s, h), vec3(s, s, h), vec3(s, -s, h)}) {
    scene.positions.push_back(p);
    scene.normals.push_back(vec3(0, 0, -1));
    scene.uvs.push_back(vec2(0.0f));
  }
  scene.triangles.push_back({base, base + 1, base + 2});
  scene.triangles.push_back({base, base + 2, base + 3});
  scene.triangle_material.push_back(1);
  scene.triangle_material.push_back(1);
  scene.finalize_bounds();
  return scene;
}

// Irradiance at plane point x from the square light, by midpoint integration on a fine grid.
double integrated_irradiance(vec3 x, float le, float s, float h) {
  const int n = 1000;
  double sum = 0.0, cell = 2.0 * s / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double px = -s + (i + 0.5) * cell - x.x, py = -s + (j + 0.5) * cell - x.y;
      double d2 = px * px + py * py + double(h) * h;
      sum += double(h) * h / (d2 * d2);  // cos at x times cos at the light, over d^2
    }
  return le * sum * cell * cell;
}

TEST(PathTracerAnalytic, EmissiveQuadOverLambertPlaneMatchesIntegratedIrradiance) {
  const float albedo = 0.5f, le = 3.0f, s = 0.25f, h = 0.6f;
  Prepared p(area_light_over_plane(albedo, le, s, h, true));
  PathTracerParams params;
  params.max_bounces = 0;
  for (vec3 x : {vec3(0.0f), vec3(0.2f, 0.1f, 0.0f), vec3(0.8f, -0.5f, 0.0f)}) {
    double expected = albedo / kPi * integrated_irradiance(x, le, s, h);
    const int n = 40000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      Ray ray;
      ray.origin = x + vec3(0, 0, 0.3f);  // below the light, looking straight down
      ray.direction = vec3(0, 0, -1);
      PixelSampler sampler = pixel_sampler(5, 77, uint32_t(i));
      RayCounters counters;
      PathSample ps = trace_path(p.context, params, ray, sampler, counters);
      double v = ps.direct.x;
      sum += v;
      sum2 += v * v;
    }
    double mean = sum / n, error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 5.0 * error) << "at " << x.x << "," << x.y << " rel " << mean / expected - 1.0;
  }
}

}  // namespace
}  // namespace sst
