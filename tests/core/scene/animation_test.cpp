#include "core/scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/scene/gltf_loader.h"
#include "tests/core/scene/gltf_test_files.h"
#include "tests/test_util.h"

namespace sst {
namespace {
using test::expect_one_line_naming;
using test::GltfBuilder;
using test::has_warning;
using test::json;
using test::kFloat;
using test::load_error;
namespace fs = std::filesystem;

constexpr int kSignedByte = 5120, kShort = 5122;
const float kHalfSqrt2 = float(std::sqrt(0.5));

void expect_near(vec3 a, vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol) << "y " << a.y << " z " << a.z;
  EXPECT_NEAR(a.y, b.y, tol) << "x " << a.x << " z " << a.z;
  EXPECT_NEAR(a.z, b.z, tol) << "x " << a.x << " y " << a.y;
}

// Adds a sampler and a channel on node.path to animation `animation` (created on first use).
// `values` are 3 or 4 floats a key (x3 for CUBICSPLINE); returns the sampler's index.
int add_channel(GltfBuilder& b, int node, const std::string& path, const std::vector<float>& times,
                const std::vector<float>& values, const std::string& interpolation = "LINEAR", size_t animation = 0) {
  while (b.doc["animations"].size() <= animation)
    b.doc["animations"].push_back({{"name", "anim" + std::to_string(b.doc["animations"].size())},
                                   {"channels", json::array()},
                                   {"samplers", json::array()}});
  json& a = b.doc["animations"][animation];
  int comps = path == "rotation" ? 4 : 3;
  int input = b.accessor(b.view(times), kFloat, times.size(), "SCALAR");
  int output = b.accessor(b.view(values), kFloat, values.size() / comps, comps == 4 ? "VEC4" : "VEC3");
  a["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
  int sampler = int(a["samplers"].size()) - 1;
  a["channels"].push_back({{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}});
  return sampler;
}

// A scene of one triangle (z = 0, facing +Z, vertices (0,0,0), (1,0,0), (0,1,0)) on node 0.
GltfBuilder triangle_scene(const json& node_fields = json::object()) {
  GltfBuilder b;
  json n = node_fields;
  n["mesh"] = b.triangle_mesh();
  b.scene({b.node(n)});
  return b;
}

// A file with camera 0 (perspective) and light 0 of `type` (a spot light's cone 0.2 to 0.4), for
// nodes to use.
GltfBuilder with_camera_and_light(const std::string& type) {
  GltfBuilder b;
  json light = {{"type", type}, {"intensity", 10.0}};
  if (type == "spot") light["spot"] = {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.4}};
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}});
  return b;
}

Scene load(GltfBuilder& b, const std::string& name = "scene") {
  return load_gltf(b.write(test::temp_dir(), name).string());
}

// A file loaded (the rest pose) and posed at t. The loader's vertex order within a primitive is
// its own business, so vertices are found by where they were at rest.
struct Posed {
  Scene rest, scene;
  vec3 offset(size_t vertex) const { return scene.positions.at(vertex) - rest.positions.at(vertex); }
  size_t vertex_at(vec3 rest_position) const {
    for (size_t i = 0; i < rest.positions.size(); ++i)
      if (glm::distance(rest.positions[i], rest_position) < 1e-6f) return i;
    ADD_FAILURE() << "no vertex at rest at " << rest_position.x << " " << rest_position.y << " " << rest_position.z;
    return 0;
  }
  vec3 at(vec3 rest_position) const { return scene.positions[vertex_at(rest_position)]; }
};

Posed posed(GltfBuilder& b, double t) {
  Posed p{load(b), {}};
  p.scene = p.rest;
  if (!p.scene.animation) throw std::runtime_error("no animation loaded");
  p.scene.animation->pose(p.scene, t);
  return p;
}

constexpr double kPiDouble = 3.14159265358979323846;

vec3 rotated_about_z(vec3 p, double degrees) {
  double r = degrees * kPiDouble / 180.0, c = std::cos(r), s = std::sin(r);
  return vec3(float(c * p.x - s * p.y), float(s * p.x + c * p.y), p.z);
}

// ---- interpolation ----

TEST(SceneAnimation, LinearTranslationInterpolatesAndMovesTheBounds) {
  GltfBuilder b = triangle_scene();
  add_channel(b, 0, "translation", {0, 2}, {0, 0, 0, 4, 2, 0});
  Posed p = posed(b, 0.5);
  const Scene& s = p.scene;
  for (size_t v = 0; v < 3; ++v) expect_near(p.offset(v), vec3(1.0f, 0.5f, 0));
  expect_near(s.bounds.lo, vec3(1.0f, 0.5f, 0));
  expect_near(s.bounds.hi, vec3(2.0f, 1.5f, 0));
  EXPECT_DOUBLE_EQ(s.animation->start_time(), 0.0);
  EXPECT_DOUBLE_EQ(s.animation->end_time(), 2.0);
}

TEST(SceneAnimation, StepHoldsEachKeyUntilTheNext) {
  GltfBuilder b = triangle_scene();
  add_channel(b, 0, "translation", {0, 1, 2}, {0, 0, 0, 5, 0, 0, 9, 0, 0}, "STEP");
  EXPECT_FLOAT_EQ(posed(b, 0.99).offset(0).x, 0.0f);
  EXPECT_FLOAT_EQ(posed(b, 1.0).offset(0).x, 5.0f);
  EXPECT_FLOAT_EQ(posed(b, 1.5).offset(0).x, 5.0f);
  EXPECT_FLOAT_EQ(posed(b, 2.0).offset(0).x, 9.0f);
}

TEST(SceneAnimation, LinearRotationIsSlerpAtConstantAngularSpeed) {
  AnimationChannel c;
  c.property = AnimatedProperty::Rotation;
  c.times = {0.0, 1.0};
  c.values = {0, 0, 0, 1, 0, 0, std::sqrt(0.5), std::sqrt(0.5)};  // 0 and 90 degrees about Z
  for (double s : {0.25, 0.5, 0.75}) {
    glm::dvec4 q = sample_channel(c, s);
    double half = s * kPiDouble / 4;  // normalised lerp would give 21.6 instead of 22.5 degrees at s = 0.25
    EXPECT_NEAR(q.z, std::sin(half), 1e-12) << s;
    EXPECT_NEAR(q.w, std::cos(half), 1e-12) << s;
  }
}

TEST(SceneAnimation, SlerpTakesTheShortestArc) {
  // The second key is -q of +90 degrees about Z: the same rotation, so the midpoint is +45, not
  // the -135 of the long way round.
  GltfBuilder b = triangle_scene();
  add_channel(b, 0, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, -kHalfSqrt2, -kHalfSqrt2});
  Posed p = posed(b, 0.5);
  expect_near(p.at({1, 0, 0}), rotated_about_z(vec3(1, 0, 0), 45.0));
  expect_near(p.at({0, 1, 0}), rotated_about_z(vec3(0, 1, 0), 45.0));
  expect_near(p.scene.normals[0], vec3(0, 0, 1));
}

TEST(SceneAnimation, NormalsTheFileLacksFollowTheTurnedFaces) {
  GltfBuilder b;
  int flat = b.mesh({{"attributes", {{"POSITION", b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0})}}}});  // no NORMAL
  b.scene({b.node({{"mesh", flat}})});
  add_channel(b, 0, "rotation", {0, 1}, {0, 0, 0, 1, kHalfSqrt2, 0, 0, kHalfSqrt2});  // +90 degrees about X
  Posed p = posed(b, 1.0);
  for (size_t v = 0; v < 3; ++v) expect_near(p.scene.normals[v], vec3(0, -1, 0));
}

TEST(SceneAnimation, CubicSplineIsHermiteWithTangentsScaledByTheKeyInterval) {
  // x: p0 = 0, p1 = 1, out-tangent of key 0 = 3, in-tangent of key 1 = -1, interval 2 s, so
  // m0 = 6, m1 = -2: p(s = 0.5) = 0.125 * 6 + 0.5 - 0.125 * -2 = 1.5 (1.0 with unscaled
  // tangents), p(s = 0.25) = 0.140625 * 6 + 0.15625 - 0.046875 * -2 = 1.09375.
  GltfBuilder b = triangle_scene();
  add_channel(b, 0, "translation", {1, 3},
              {/*key 0*/ 7, 7, 7, 0, 0, 0, 3, 0, 0, /*key 1*/ -1, 0, 0, 1, 2, 0, 7, 7, 7}, "CUBICSPLINE");
  vec3 mid = posed(b, 2.0).offset(0);
  EXPECT_NEAR(mid.x, 1.5f, 1e-6f);
  EXPECT_NEAR(mid.y, 1.0f, 1e-6f);  // y: no tangents, p0 = 0, p1 = 2: 0.5 * 2
  vec3 quarter = posed(b, 1.5).offset(0);
  EXPECT_NEAR(quarter.x, 1.09375f, 1e-6f);
  EXPECT_NEAR(quarter.y, 0.3125f, 1e-6f);  // 0.15625 * 2
  expect_near(posed(b, 3.0).offset(0), vec3(1, 2, 0));  // the value, never a tangent
}

TEST(SceneAnimation, CubicSplineRotationComesOutNormalised) {
  AnimationChannel c;
  c.property = AnimatedProperty::Rotation;
  c.interpolation = Interpolation::CubicSpline;
  c.times = {0.0, 1.0};
  c.values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0,  // key 0: in, value, out
              0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};  // key 1
  glm::dvec4 q = sample_channel(c, 0.4);
  EXPECT_NEAR(glm::length(q), 1.0, 1e-12);
  EXPECT_GT(q.z, 0.0);
}

TEST(SceneAnimation, ReadsNormalizedShortAndByteRotations) {
  for (int type : {kShort, kSignedByte}) {
    GltfBuilder b = triangle_scene();
    add_channel(b, 0, "translation", {0, 1}, {0, 0, 0, 0, 0, 0});  // sampler 0
    int input = b.doc["animations"][0]["samplers"][0]["input"];
    int output;
    if (type == kShort) {
      std::vector<int16_t> q = {0, 0, 23170, 23170, 0, 0, 23170, 23170};  // 90 degrees about Z, twice
      output = b.accessor(b.view(q), kShort, 2, "VEC4", 0, true);
    } else {
      std::vector<int8_t> q = {0, 0, 90, 90, 0, 0, 90, 90};
      output = b.accessor(b.view(q), kSignedByte, 2, "VEC4", 0, true);
    }
    b.doc["animations"][0]["samplers"].push_back({{"input", input}, {"output", output}});
    b.doc["animations"][0]["channels"].push_back({{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}});
    expect_near(posed(b, 0.5).at({1, 0, 0}), vec3(0, 1, 0));
  }
}

TEST(SceneAnimation, ClampsOutsideTheKeysOfEachChannel) {
  GltfBuilder b = triangle_scene();
  add_channel(b, 0, "translation", {1, 2}, {1, 0, 0, 3, 0, 0});
  add_channel(b, 0, "scale", {0, 4}, {1, 1, 1, 2, 2, 2});
  EXPECT_DOUBLE_EQ(posed(b, 0).scene.animation->start_time(), 0.0);
  EXPECT_DOUBLE_EQ(posed(b, 0).scene.animation->end_time(), 4.0);
  expect_near(posed(b, -5.0).at({1, 0, 0}), vec3(2, 0, 0));     // translation 1, scale 1
  expect_near(posed(b, 3.0).at({1, 0, 0}), vec3(4.75f, 0, 0));  // translation past its last key, scale 1.75
  expect_near(posed(b, 100.0).at({1, 0, 0}), vec3(5, 0, 0));
}

// ---- hierarchy ----

TEST(SceneAnimation, AnimatedParentCarriesStaticChildMeshCameraAndLight) {
  GltfBuilder b = with_camera_and_light("spot");
  int mesh = b.node({{"mesh", b.triangle_mesh()}, {"translation", {0, 0, -2}}});
  int camera = b.node({{"camera", 0}, {"translation", {0, 1, 0}}});
  int light = b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  int parent = b.node({{"children", {mesh, camera, light}}, {"translation", {0, 0, 1}}});
  int still = b.node({{"mesh", b.triangle_mesh()}, {"translation", {5, 0, 0}}});
  b.scene({parent, still});
  // +90 degrees about Y at t = 1: -Z turns to -X, +X to -Z.
  add_channel(b, parent, "rotation", {0, 1}, {0, 0, 0, 1, 0, kHalfSqrt2, 0, kHalfSqrt2});
  Posed p = posed(b, 1.0);
  const Scene& s = p.scene;
  // The mesh's vertex (1,0,0) sits at (1,0,-2) in the parent, (-2,0,-1) after the turn, +Z 1.
  expect_near(p.at({0, 0, -1}), vec3(-2, 0, 1));
  expect_near(p.at({1, 0, -1}), vec3(-2, 0, 0));
  for (size_t v = 0; v < 3; ++v) expect_near(s.normals[v], vec3(1, 0, 0));
  for (size_t v = 3; v < 6; ++v) EXPECT_EQ(p.offset(v), vec3(0.0f)) << "the unanimated mesh stays";
  expect_near(s.cameras[0].eye, vec3(0, 1, 1));
  expect_near(s.cameras[0].forward, vec3(-1, 0, 0));
  expect_near(s.cameras[0].up, vec3(0, 1, 0));
  expect_near(s.lights[0].position, vec3(0, 0, 1));
  expect_near(s.lights[0].direction, vec3(-1, 0, 0));
  json summary = s.animation->summary();
  EXPECT_EQ(summary["channels"], 1);
  EXPECT_EQ(summary["animated_nodes"], 4);
  EXPECT_EQ(summary["animated_meshes"], 1);
  EXPECT_EQ(summary["animated_vertices"], 3);
  EXPECT_EQ(summary["animated_cameras"], 1);
  EXPECT_EQ(summary["animated_lights"], 1);
  EXPECT_EQ(summary["interpolations"], json::array({"LINEAR"}));
}

TEST(SceneAnimation, PoseChangeSaysWhatMoved) {
  GltfBuilder b = with_camera_and_light("point");
  int mesh = b.node({{"mesh", b.triangle_mesh()}});
  int camera = b.node({{"camera", 0}});
  int light = b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.scene({mesh, camera, light});
  add_channel(b, mesh, "translation", {0, 1}, {0, 0, 0, 1, 0, 0});
  add_channel(b, camera, "translation", {2, 3}, {0, 0, 0, 0, 1, 0});
  add_channel(b, light, "translation", {4, 5}, {0, 0, 0, 0, 0, 1});
  Scene s = load(b);
  auto flags = [](PoseChange c) { return std::vector<bool>{c.geometry, c.cameras, c.lights}; };
  EXPECT_EQ(flags(s.animation->pose(s, 0.0)), std::vector<bool>({false, false, false}));  // the rest pose
  EXPECT_EQ(flags(s.animation->pose(s, 0.5)), std::vector<bool>({true, false, false}));
  EXPECT_EQ(flags(s.animation->pose(s, 0.5)), std::vector<bool>({false, false, false}));
  EXPECT_EQ(flags(s.animation->pose(s, 2.5)), std::vector<bool>({true, true, false}));
  EXPECT_EQ(flags(s.animation->pose(s, 4.5)), std::vector<bool>({false, true, true}));  // camera reaches its end
  EXPECT_EQ(flags(s.animation->pose(s, 9.0)), std::vector<bool>({false, false, true}));
}

TEST(SceneAnimation, StaticSceneHasNoAnimation) {
  GltfBuilder b = triangle_scene();
  EXPECT_EQ(load(b).animation, nullptr);
  // A channel on a node outside the rendered scene moves nothing either.
  int loose = b.node({{"translation", {1, 2, 3}}});
  add_channel(b, loose, "translation", {0, 1}, {0, 0, 0, 1, 0, 0});
  EXPECT_EQ(load(b).animation, nullptr);
}

// Posing a file whose channels hold the rest values gives the loader's scene to the bit: mirrored
// and non-uniform scale, a rotated parent, smooth, flat and zero normals, a camera, a spot light.
TEST(SceneAnimation, IdentityAnimationPosesTheLoadersBits) {
  GltfBuilder b = with_camera_and_light("spot");
  int pos = b.vec3s({0, 0, 0, 1, 0.1f, 0, 0, 1, 0.3f, 1, 1, 0.7f});
  int nrm = b.vec3s({0, 0, 1, 0.3f, 0, 0.9f, 0, 0, 0, 0, 0.2f, 1});  // a zero one
  int idx = b.indices(std::vector<uint16_t>{0, 1, 2, 2, 1, 3}, test::kUShort);
  int smooth = b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}});
  int flat = b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
  std::vector<float> t = {0.25f, -1.5f, 3.0f}, q = {0.1f, 0.6f, -0.2f, 0.7f}, sc = {1.5f, -0.5f, 2.0f};
  int child = b.node({{"mesh", flat}, {"translation", {0.5, 0.25, -1}}, {"scale", {1, 2, 1}}});
  int camera = b.node({{"camera", 0}, {"rotation", {0, 0.38268343, 0, 0.92387953}}});
  int light = b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {0, 3, 0}}});
  int parent = b.node({{"mesh", smooth}, {"children", {child, camera, light}}, {"translation", t}, {"rotation", q}, {"scale", sc}});
  b.scene({parent});
  add_channel(b, parent, "translation", {0, 1}, {t[0], t[1], t[2], t[0], t[1], t[2]});
  add_channel(b, parent, "rotation", {0, 1}, {q[0], q[1], q[2], q[3], q[0], q[1], q[2], q[3]});
  add_channel(b, parent, "scale", {0, 2}, {0, 0, 0, sc[0], sc[1], sc[2], 0, 0, 0, 0, 0, 0, sc[0], sc[1], sc[2], 0, 0, 0},
              "CUBICSPLINE");
  Scene loaded = load(b);
  ASSERT_TRUE(loaded.animation);
  ASSERT_TRUE(has_warning(loaded, "zero-length vertex normals"));
  Scene s = loaded;
  s.animation->pose(s, 1.3);  // away and back: the pose is a function of t alone
  s.animation->pose(s, s.animation->start_time());
  auto same = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  EXPECT_TRUE(same(s.positions, loaded.positions));
  EXPECT_TRUE(same(s.normals, loaded.normals));
  EXPECT_EQ(std::memcmp(&s.bounds, &loaded.bounds, sizeof s.bounds), 0);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(std::memcmp(&s.cameras[0].eye, &loaded.cameras[0].eye, sizeof(vec3)), 0);
  EXPECT_EQ(std::memcmp(&s.cameras[0].forward, &loaded.cameras[0].forward, sizeof(vec3)), 0);
  EXPECT_EQ(std::memcmp(&s.cameras[0].up, &loaded.cameras[0].up, sizeof(vec3)), 0);
  EXPECT_EQ(std::memcmp(&s.lights[0].position, &loaded.lights[0].position, sizeof(vec3)), 0);
  EXPECT_EQ(std::memcmp(&s.lights[0].direction, &loaded.lights[0].direction, sizeof(vec3)), 0);
}

// ---- what the loader ignores, and how it plays several animations ----

TEST(SceneAnimation, SeveralAnimationsPlayTogetherAndTheLaterWinsATarget) {
  GltfBuilder b;
  int a = b.node({{"mesh", b.triangle_mesh()}});
  int c = b.node({{"mesh", b.triangle_mesh()}});
  b.scene({a, c});
  add_channel(b, a, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}, "LINEAR", 0);
  add_channel(b, c, "translation", {0, 1}, {0, 0, 0, 0, 1, 0}, "LINEAR", 1);
  add_channel(b, a, "translation", {0, 1}, {0, 0, 0, 0, 0, 2}, "LINEAR", 1);
  Posed p = posed(b, 1.0);
  expect_near(p.offset(0), vec3(0, 0, 2));
  expect_near(p.offset(3), vec3(0, 1, 0));
  EXPECT_TRUE(has_warning(p.scene, "node 0 translation is animated by animation 0 ('anim0') and animation 1 ('anim1')"));
}

TEST(SceneAnimation, SkinsAndMorphWeightsAreIgnoredWithAWarningEach) {
  GltfBuilder b = triangle_scene();
  b.doc["skins"] = json::array({{{"joints", {0}}}});
  add_channel(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0});
  int input = b.doc["animations"][0]["samplers"][0]["input"];
  int weights = b.accessor(b.view(std::vector<float>{0, 1}), kFloat, 2, "SCALAR");
  b.doc["animations"][0]["samplers"].push_back({{"input", input}, {"output", weights}});
  b.doc["animations"][0]["channels"].push_back({{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}});
  Posed p = posed(b, 1.0);
  expect_near(p.offset(0), vec3(1, 0, 0));
  EXPECT_TRUE(has_warning(p.scene, "skins ignored"));
  EXPECT_TRUE(has_warning(p.scene, "animated morph target weights ignored (1 channels)"));
}

// ---- bad input: one line naming the file, the animation, channel or sampler, and the problem ----

class AnimationErrors : public ::testing::Test {
 protected:
  GltfBuilder b = triangle_scene();
  void SetUp() override { add_channel(b, 0, "translation", {0, 1}, {0, 0, 0, 1, 0, 0}); }
  json& channel() { return b.doc["animations"][0]["channels"][0]; }
  json& sampler() { return b.doc["animations"][0]["samplers"][0]; }
  void expect_error(const std::string& problem) {
    fs::path path = b.write(test::temp_dir(), "bad");
    expect_one_line_naming(load_error(path), path, problem);
  }
};

TEST_F(AnimationErrors, MissingSampler) {
  channel()["sampler"] = 5;
  expect_error("animation 0 ('anim0') channel 0 refers to missing sampler 5");
}

TEST_F(AnimationErrors, MissingAccessor) {
  sampler()["output"] = 99;
  expect_error("animation 0 ('anim0') channel 0 sampler 0 output refers to missing accessor 99");
}

TEST_F(AnimationErrors, MissingNode) {
  channel()["target"]["node"] = 42;
  expect_error("animation 0 ('anim0') channel 0 targets missing node 42");
}

TEST_F(AnimationErrors, NodeWithAMatrix) {
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  expect_error("channel 0 targets node 0 translation, but the node has a matrix");
}

TEST_F(AnimationErrors, NonIncreasingTimes) {
  sampler()["input"] = b.accessor(b.view(std::vector<float>{0, 1, 1}), kFloat, 3, "SCALAR");
  sampler()["output"] = b.vec3s({0, 0, 0, 1, 0, 0, 2, 0, 0});
  expect_error("channel 0 sampler 0 input times are not strictly increasing at key 2");
}

TEST_F(AnimationErrors, NonFiniteTime) {
  sampler()["input"] = b.accessor(b.view(std::vector<float>{0, std::numeric_limits<float>::quiet_NaN()}), kFloat, 2, "SCALAR");
  expect_error("channel 0 sampler 0 input has a non-finite time at key 1");
}

TEST_F(AnimationErrors, OutputCountMismatch) {
  sampler()["output"] = b.vec3s({0, 0, 0, 1, 0, 0, 2, 0, 0});
  expect_error("channel 0 sampler 0 output has 3 elements for 2 key times (LINEAR needs 2)");
}

TEST_F(AnimationErrors, CubicSplineNeedsThreeOutputsAKey) {
  sampler()["interpolation"] = "CUBICSPLINE";
  expect_error("channel 0 sampler 0 output has 2 elements for 2 key times (CUBICSPLINE needs 6)");
}

TEST_F(AnimationErrors, UnknownInterpolation) {
  sampler()["interpolation"] = "QUADRATIC";
  expect_error("channel 0 sampler 0 has unknown interpolation 'QUADRATIC'");
}

TEST_F(AnimationErrors, WrongOutputType) {
  channel()["target"]["path"] = "rotation";  // VEC3 output for a VEC4 property
  int output = sampler()["output"];
  expect_error("channel 0 sampler 0 output (accessor " + std::to_string(output) +
               ") has 3 components per element (needs 4)");
}

TEST_F(AnimationErrors, UnnormalizedIntegerRotation) {
  channel()["target"]["path"] = "rotation";
  int output = b.accessor(b.view(std::vector<int16_t>{0, 0, 0, 1, 0, 0, 0, 1}), kShort, 2, "VEC4");
  sampler()["output"] = output;
  expect_error("channel 0 sampler 0 output (accessor " + std::to_string(output) + ") has unsupported componentType 5122");
}

TEST_F(AnimationErrors, WrongInputType) {
  int input = b.vec3s({0, 0, 0, 1, 0, 0});
  sampler()["input"] = input;
  expect_error("channel 0 sampler 0 input (accessor " + std::to_string(input) + ") has 3 components per element (needs 1)");
}

// ---- the scene that ships ----

TEST(SceneAnimation, ShippedAnimatedBoxMovesItsBoxAndCamera) {
  Scene s = load_gltf(std::string(SST_SOURCE_DIR) + "/scenes/animated_box.gltf");
  ASSERT_TRUE(s.animation);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_DOUBLE_EQ(s.animation->start_time(), 0.0);
  EXPECT_DOUBLE_EQ(s.animation->end_time(), 2.0);
  s.animation->pose(s, 0.0);
  Scene later = s;
  PoseChange change = later.animation->pose(later, 1.0);
  EXPECT_TRUE(change.geometry);
  EXPECT_TRUE(change.cameras);
  EXPECT_FALSE(change.lights);
  EXPECT_GT(glm::distance(later.cameras[0].eye, s.cameras[0].eye), 0.1f);
}

}  // namespace
}  // namespace sst
