// Motion vectors and reprojection: analytic cameras and moving geometry, to within 0.01 pixel.
#include <gtest/gtest.h>

#include "core/accel/embree_accel.h"
#include "core/render/camera.h"
#include "core/render/centre_gbuffer.h"
#include "core/render/pinhole.h"
#include "core/render/reprojection.h"
#include "tests/analytic_scenes.h"

namespace sst {
namespace {

glsl::ViewParams view_of(const Camera& c, int w, int h) { return view_params(PinholeCamera(c, w, h), w, h, 0); }

TEST(Reprojection, ProjectingAPointOnAPixelRayGivesThePixelBack) {
  Camera c;
  c.eye = vec3(1.0f, 2.0f, 3.0f);
  c.forward = glm::normalize(vec3(0.3f, -0.2f, -1.0f));
  c.up = glm::normalize(vec3(0.0f, 1.0f, 0.0f) - glm::dot(vec3(0, 1, 0), c.forward) * c.forward);
  c.yfov = 0.9f;
  glsl::ViewParams v = view_of(c, 200, 120);
  for (vec2 px : {vec2(0.5f, 0.5f), vec2(100.0f, 60.0f), vec2(199.5f, 3.25f), vec2(17.75f, 119.5f)}) {
    vec3 p = v.eye + 7.0f * camera_direction(v, px.x, px.y);
    vec2 back;
    float distance;
    ASSERT_TRUE(project_to_pixel(v, p, back, distance));
    EXPECT_NEAR(back.x, px.x, 1e-3f);
    EXPECT_NEAR(back.y, px.y, 1e-3f);
    EXPECT_NEAR(distance, 7.0f, 1e-4f);
  }
  vec2 behind;
  float d;
  EXPECT_FALSE(project_to_pixel(v, v.eye - v.forward, behind, d));
}

// The plane z = 0 seen straight down from height 2: a camera translated by (dx, 0, 0) sees a
// fixed point move by -dx over the image's world width at that depth, in pixels.
TEST(MotionVectors, TranslatedCameraMatchesTheAnalyticMotion) {
  const float yfov = 0.8f, height = 2.0f, dx = 0.05f;
  const int w = 64, h = 48;
  Scene scene = test::lambert_plane(0.5f, 50.0f, height, yfov);
  EmbreeAccel accel(scene, false);
  Camera now = scene.cameras[0];
  now.aspect = float(w) / float(h);
  Camera before = now;
  before.eye.x -= dx;  // the camera moved +dx since the previous frame
  CentreGBuffer m = centre_gbuffer(accel, scene, scene.positions, view_of(now, w, h), view_of(before, w, h));
  glsl::ViewParams v = view_of(now, w, h);
  // Pixels per world unit at depth `height` along the camera's right axis.
  float pixels_per_unit = float(w) / (2.0f * height * v.tan_half_y * v.aspect);
  float expected = glm::dot(vec3(dx, 0.0f, 0.0f), v.right) * pixels_per_unit;
  for (int y = 0; y < h; y += 7)
    for (int x = 0; x < w; x += 5) {
      EXPECT_NEAR(m.motion.at(x, y, 0), expected, 0.01f) << x << "," << y;
      EXPECT_NEAR(m.motion.at(x, y, 1), 0.0f, 0.01f) << x << "," << y;
      EXPECT_GT(m.previous_depth.at(x, y, 0), 0.0f);
    }
}

// Geometry that moved: the previous positions are the plane shifted by -d (it moved +d since),
// so each point was seen where its shifted copy projects with the same camera.
TEST(MotionVectors, MovingGeometryMatchesTheAnalyticMotion) {
  const float yfov = 0.8f, height = 2.0f;
  const vec3 d(0.0f, 0.04f, 0.0f);
  const int w = 64, h = 64;
  Scene scene = test::lambert_plane(0.5f, 50.0f, height, yfov);
  EmbreeAccel accel(scene, false);
  std::vector<vec3> previous = scene.positions;
  for (vec3& p : previous) p -= d;
  Camera cam = scene.cameras[0];
  cam.aspect = 1.0f;
  glsl::ViewParams v = view_of(cam, w, h);
  CentreGBuffer m = centre_gbuffer(accel, scene, previous, v, v);
  float pixels_per_unit = float(h) / (2.0f * height * v.tan_half_y);
  // The point moved +d: it was where -d projects; on screen that is -d . up upward, i.e. +y down.
  float expected_y = glm::dot(d, v.up) * pixels_per_unit;
  float expected_x = -glm::dot(d, v.right) * pixels_per_unit;
  for (int y = 0; y < h; y += 9)
    for (int x = 0; x < w; x += 9) {
      EXPECT_NEAR(m.motion.at(x, y, 0), expected_x, 0.01f);
      EXPECT_NEAR(m.motion.at(x, y, 1), expected_y, 0.01f);
    }
}

}  // namespace
}  // namespace sst
