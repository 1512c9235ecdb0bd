#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/scene/scene_access.h"
#include "core/util/error.h"
#include "tests/core/scene/gltf_test_files.h"
#include "tests/test_util.h"

namespace sst {
namespace {
using nlohmann::json;
namespace fs = std::filesystem;

using test::expect_one_line_naming;
using test::GltfBuilder;
using test::has_warning;
using test::kByte;
using test::kFloat;
using test::kUInt;
using test::kUShort;
using test::load_error;
using test::write_png;

void expect_near(vec3 a, vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

vec3 geometric_normal(const Scene& s, size_t t) {
  uvec3 tri = s.triangles[t];
  return glm::normalize(glm::cross(s.positions[tri.y] - s.positions[tri.x], s.positions[tri.z] - s.positions[tri.x]));
}


// A material whose baseColorTexture is the image `uri`.
GltfBuilder textured_triangle(const std::string& uri) {
  GltfBuilder b;
  b.doc["images"] = json::array({{{"uri", uri}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  int mat = b.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  b.scene({b.node({{"mesh", b.triangle_mesh(mat)}})});
  return b;
}

// ---- errors ----

TEST(GltfLoader, MissingFileIsAnErrorNamingIt) {
  fs::path p = test::temp_dir() / "nope.gltf";
  expect_one_line_naming(load_error(p), p, "not found");
}

TEST(GltfLoader, MalformedJsonIsAnError) {
  fs::path p = test::temp_dir() / "bad.gltf";
  std::ofstream(p) << "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ }";
  expect_one_line_naming(load_error(p), p, "malformed JSON");
}

TEST(GltfLoader, MissingBufferFileIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  fs::path p = b.write(dir, "scene");
  fs::remove(dir / "scene.bin");
  expect_one_line_naming(load_error(p), p, "buffer file not found: scene.bin");
}

TEST(GltfLoader, ShortBufferFileIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  fs::path p = b.write(dir, "scene");
  fs::resize_file(dir / "scene.bin", 20);
  expect_one_line_naming(load_error(p), p, "scene.bin has 20 bytes, the glTF says 72");
}

TEST(GltfLoader, AccessorBeyondItsBufferViewIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  b.doc["accessors"][0]["count"] = 4;  // 48 bytes wanted from a 36-byte view
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "reaches beyond bufferView 0");
}

TEST(GltfLoader, BufferViewBeyondItsBufferIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  b.doc["bufferViews"][1]["byteOffset"] = 1000;
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "buffer 0 is too short for bufferView 1");
}

TEST(GltfLoader, IndexOutOfRangeIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int idx = b.indices(std::vector<uint16_t>{0, 1, 3, 0, 0}, kUShort);  // 5 elements keep the view 4-aligned
  b.doc["accessors"][idx]["count"] = 3;
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "vertex index 3 out of range (vertex count 3)");
}

TEST(GltfLoader, NanVertexIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, std::nanf(""), 0, 0, 1, 0});
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}})}})});
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "POSITION has a non-finite value (NaN or Inf) at vertex 1");
}

TEST(GltfLoader, UnsupportedRequiredExtensionIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  b.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  b.doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "requires unsupported extension EXT_meshopt_compression");
}

TEST(GltfLoader, AcceptedRequiredExtensionLoads) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  EXPECT_EQ(load_gltf(b.write(dir, "scene").string()).triangles.size(), 1u);
}

TEST(GltfLoader, SceneWithoutTrianglesIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 0}})}})});  // POINTS
  fs::path p = b.write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "scene has no triangles");
  GltfBuilder empty;
  empty.scene({empty.node({{"name", "nothing"}})});
  fs::path q = empty.write(dir, "empty");
  expect_one_line_naming(load_error(q), q, "scene has no triangles");
}

TEST(GltfLoader, MissingImageIsAnErrorNamingIt) {
  fs::path dir = test::temp_dir();
  fs::path p = textured_triangle("missing-texture.png").write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "missing-texture.png");
}

TEST(GltfLoader, NodeCycleIsAnError) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int m = b.triangle_mesh();
  b.node({{"mesh", m}, {"children", {1}}});
  b.node({{"children", {0}}});
  b.scene({0});
  fs::path p = b.write(dir, "scene");
  std::string msg = load_error(p);
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("node"), std::string::npos) << msg;
}

// ---- geometry ----

TEST(GltfLoader, NestedTrsHierarchyGivesWorldPositions) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({1, 0, 0, 0, 0, 0, 0, 0, 1});
  int m = b.mesh({{"attributes", {{"POSITION", pos}}}});
  const float h = std::sqrt(0.5f);
  int child = b.node({{"mesh", m}, {"rotation", {0, 0, h, h}}, {"translation", {0, 1, 0}}});  // 90 deg about Z
  int parent = b.node({{"children", {child}}, {"translation", {1, 0, 0}}, {"scale", {2, 2, 2}}});
  // The same mesh under a matrix node: translation (0, 0, 5) in column-major order.
  int mat = b.node({{"mesh", m}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}});
  b.scene({parent, mat});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 2u);
  // local (1,0,0) -> rotated (0,1,0) -> +(0,1,0) = (0,2,0) -> scaled (0,4,0) -> +(1,0,0)
  expect_near(s.positions[s.triangles[0].x], vec3(1, 4, 0));
  expect_near(s.positions[s.triangles[0].y], vec3(1, 2, 0));
  expect_near(s.positions[s.triangles[0].z], vec3(1, 2, 2));
  expect_near(s.positions[s.triangles[1].x], vec3(1, 0, 5));
  EXPECT_EQ(s.bounds.lo.z, 0.0f);
  EXPECT_EQ(s.bounds.hi.z, 6.0f);
}

TEST(GltfLoader, MirroredTransformFlipsWinding) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int m = b.triangle_mesh();
  b.scene({b.node({{"mesh", m}}), b.node({{"mesh", m}, {"scale", {-1, 1, 1}}}), b.node({{"mesh", m}, {"scale", {1, 1, -1}}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 3u);
  for (size_t t = 0; t < 3; ++t) {
    vec3 shading = s.normals[s.triangles[t].x];
    EXPECT_GT(glm::dot(geometric_normal(s, t), shading), 0.99f) << "triangle " << t;
  }
  expect_near(s.normals[s.triangles[1].x], vec3(0, 0, 1));   // x mirror keeps the normal
  expect_near(s.normals[s.triangles[2].x], vec3(0, 0, -1));  // z mirror turns it around
}

TEST(GltfLoader, ReadsEightSixteenAndThirtyTwoBitIndices) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  std::vector<int> nodes;
  int i8 = b.indices(std::vector<uint8_t>{0, 1, 2, 0, 2, 3, 0, 0}, kByte);
  int i16 = b.indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUShort);
  int i32 = b.indices(std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, kUInt);
  b.doc["accessors"][i8]["count"] = 6;
  for (int idx : {i8, i16, i32}) nodes.push_back(b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}}));
  b.scene(nodes);
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 6u);
  for (size_t t = 0; t < 6; t += 2) {
    expect_near(s.positions[s.triangles[t].y], vec3(1, 0, 0));
    expect_near(s.positions[s.triangles[t + 1].z], vec3(0, 1, 0));
  }
}

TEST(GltfLoader, GeneratesFlatNormalsWhenNormalIsMissing) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  // Two triangles of a folded quad sharing an edge: flat shading needs six vertices.
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1});
  int idx = b.indices(std::vector<uint16_t>{0, 1, 2, 1, 3, 2}, kUShort);
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.positions.size(), 6u);
  for (size_t t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k) expect_near(s.normals[s.triangles[t][k]], geometric_normal(s, t));
  EXPECT_TRUE(has_warning(s, "flat normals"));
}

TEST(GltfLoader, ReplacesZeroNormalsAndDropsDegenerateTriangles) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0});
  int nrm = b.vec3s({0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  int idx = b.indices(std::vector<uint16_t>{0, 1, 2, 0, 1, 3}, kUShort);  // second one is collinear
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}})}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 1u);
  expect_near(s.normals[s.triangles[0].x], vec3(0, 0, 1));
  EXPECT_TRUE(has_warning(s, "dropped 1 zero-area triangles"));
  EXPECT_TRUE(has_warning(s, "zero-length vertex normals"));
}

TEST(GltfLoader, KeepsTinyTriangles) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1e-13f, 0, 0, 0, 1e-13f, 0});  // |cross|^2 underflows in float
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}})}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 1u);
  expect_near(s.normals[0], vec3(0, 0, 1));
}

TEST(GltfLoader, ConvertsStripsAndFans) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  int strip = b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 5}});
  int fan = b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 6}});
  int lines = b.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 1}});
  b.scene({b.node({{"mesh", strip}}), b.node({{"mesh", fan}}), b.node({{"mesh", lines}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 4u);
  // Strip (0,1,2), (2,1,3): both face +Z. Fan (1,2,0), (2,3,0): the second is (0,1,0),(1,1,0),(0,0,0) -> -Z.
  EXPECT_GT(geometric_normal(s, 0).z, 0.99f);
  EXPECT_GT(geometric_normal(s, 1).z, 0.99f);
  EXPECT_GT(geometric_normal(s, 2).z, 0.99f);
  EXPECT_LT(geometric_normal(s, 3).z, -0.99f);
  EXPECT_TRUE(has_warning(s, "LINES primitives skipped"));
}

TEST(GltfLoader, ReadsInterleavedAttributesAndNormalizedUvs) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
  int v = b.view(interleaved, 24);
  int pos = b.accessor(v, kFloat, 3, "VEC3");
  int nrm = b.accessor(v, kFloat, 3, "VEC3", 12);
  int uv = b.accessor(b.view(std::vector<uint16_t>{0, 0, 65535, 0, 0, 32768}), kUShort, 3, "VEC2", 0, true);
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}})}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.triangles.size(), 1u);
  expect_near(s.positions[s.triangles[0].y], vec3(1, 0, 0));
  expect_near(s.normals[s.triangles[0].y], vec3(0, 0, 1));
  EXPECT_NEAR(s.uvs[s.triangles[0].y].x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].z].y, 32768.0f / 65535.0f, 1e-6f);
}

TEST(GltfLoader, LoadsGlb) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  fs::path p = b.write_glb(dir, "scene");
  Scene s = load_gltf(p.string());
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.source, p.string());
}

TEST(GltfLoader, LoadsFromMemoryWithEmbeddedBuffer) {
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  json d = b.doc;
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  for (size_t i = 0; i < b.bin.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(b.bin[i])) << 16;
    if (i + 1 < b.bin.size()) n |= uint32_t(uint8_t(b.bin[i + 1])) << 8;
    if (i + 2 < b.bin.size()) n |= uint8_t(b.bin[i + 2]);
    b64 += abc[(n >> 18) & 63];
    b64 += abc[(n >> 12) & 63];
    b64 += i + 1 < b.bin.size() ? abc[(n >> 6) & 63] : '=';
    b64 += i + 2 < b.bin.size() ? abc[n & 63] : '=';
  }
  d["buffers"] = json::array({{{"uri", "data:application/octet-stream;base64," + b64}, {"byteLength", b.bin.size()}}});
  Scene s = load_gltf_from_memory(d.dump(), "", "memory:test");
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.source, "memory:test");
}

// ---- materials and textures ----

TEST(GltfLoader, MaterialFactorsEmissionAndDefaultMaterial) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int mat = b.material({{"name", "lamp"},
                        {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 0.125, 0.5}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}},
                        {"emissiveFactor", {1.0, 0.5, 0.0}},
                        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 10.0}}}}},
                        {"doubleSided", true}});
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.scene({b.node({{"mesh", b.triangle_mesh(mat)}}), b.node({{"mesh", b.triangle_mesh()}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& m = s.materials[s.triangle_material[0]];
  EXPECT_EQ(m.name, "lamp");
  expect_near(m.base_color, vec3(0.5f, 0.25f, 0.125f));
  EXPECT_EQ(m.metallic, 0.0f);
  EXPECT_EQ(m.roughness, 0.5f);
  expect_near(m.emission, vec3(10.0f, 5.0f, 0.0f));
  EXPECT_TRUE(m.double_sided);
  const Material& def = s.materials[s.triangle_material[1]];
  expect_near(def.base_color, vec3(1.0f));
  EXPECT_EQ(def.metallic, 1.0f);
  EXPECT_EQ(def.roughness, 1.0f);
  EXPECT_FALSE(has_warning(s, "no lights"));
}

TEST(GltfLoader, DecodesSrgbAndLinearTexturesWithSamplerModes) {
  fs::path dir = test::temp_dir();
  write_png(dir / "tex.png", 2, 1, 8, 2, {0, 128, 255, 255, 10, 0});
  GltfBuilder b;
  b.doc["images"] = json::array({{{"uri", "tex.png"}}});
  b.doc["samplers"] = json::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 0}}});
  int mat = b.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
                        {"emissiveTexture", {{"index", 1}}}});
  b.scene({b.node({{"mesh", b.triangle_mesh(mat)}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  const Material& m = s.materials[0];
  ASSERT_EQ(s.textures.size(), 3u);  // (image, sRGB, sampler 0), (image, linear, sampler 0), (image, sRGB, none)
  const Texture& srgb = s.textures[m.base_color_texture];
  const Texture& linear = s.textures[m.metallic_roughness_texture];
  const Texture& repeat = s.textures[m.emissive_texture];
  ASSERT_EQ(srgb.width, 2);
  ASSERT_EQ(srgb.height, 1);
  auto exact_srgb = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
  EXPECT_EQ(srgb.texel(0).x, 0.0f);
  EXPECT_NEAR(srgb.texel(0).y, exact_srgb(128.0f / 255.0f), 1e-6f);
  EXPECT_NEAR(srgb.texel(0).y, 0.2158605f, 1e-6f);
  EXPECT_NEAR(srgb.texel(1).y, 10.0f / 255.0f / 12.92f, 1e-7f);  // the linear segment
  EXPECT_EQ(srgb.texel(0).z, 1.0f);
  EXPECT_EQ(srgb.texel(0).w, 1.0f);
  EXPECT_NEAR(linear.texel(0).y, 128.0f / 255.0f, 1e-6f);
  EXPECT_EQ(srgb.wrap_s, Wrap::ClampToEdge);
  EXPECT_EQ(srgb.wrap_t, Wrap::MirroredRepeat);
  EXPECT_TRUE(srgb.nearest);
  EXPECT_EQ(repeat.wrap_s, Wrap::Repeat);
  EXPECT_EQ(repeat.wrap_t, Wrap::Repeat);
  EXPECT_FALSE(repeat.nearest);
}

TEST(GltfLoader, ExpandsGreyAlphaTexturesToRgba) {
  fs::path dir = test::temp_dir();
  write_png(dir / "grey.png", 2, 1, 8, 4, {255, 51, 0, 255});
  GltfBuilder b = textured_triangle("grey.png");
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].texel(0), vec4(1.0f, 1.0f, 1.0f, 0.2f));  // alpha stays linear
  EXPECT_EQ(s.textures[0].texel(1), vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

TEST(GltfLoader, DecodesSixteenBitTextures) {
  fs::path dir = test::temp_dir();
  write_png(dir / "deep.png", 2, 1, 16, 0, {0x80, 0x00, 0xFF, 0xFF});
  Scene s = load_gltf(textured_triangle("deep.png").write(dir, "scene").string());
  ASSERT_EQ(s.textures.size(), 1u);
  float c = 32768.0f / 65535.0f;
  EXPECT_NEAR(s.textures[0].texel(0).x, std::pow((c + 0.055f) / 1.055f, 2.4f), 1e-6f);
  EXPECT_EQ(s.textures[0].texel(1), vec4(1.0f));
}

TEST(GltfLoader, ImagesOtherThanPngOrJpegAreAnError) {
  fs::path dir = test::temp_dir();
  std::ofstream(dir / "tex.ppm", std::ios::binary) << "P6\n1 1\n255\nabc";
  fs::path p = textured_triangle("tex.ppm").write(dir, "scene");
  expect_one_line_naming(load_error(p), p, "'tex.ppm' is neither PNG nor JPEG");
}

// A triangle with two UV sets: TEXCOORD_0 = (0,0), (1,0), (0,1) and TEXCOORD_1 = (0.5,0.5), (1,0.5),
// (0.5,1), and a baseColorTexture.
GltfBuilder triangle_with_two_uv_sets() {
  GltfBuilder b = textured_triangle("tex.png");
  json& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["TEXCOORD_0"] = b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 0, 1}), kFloat, 3, "VEC2");
  prim["attributes"]["TEXCOORD_1"] = b.accessor(b.view(std::vector<float>{0.5f, 0.5f, 1, 0.5f, 0.5f, 1}), kFloat, 3, "VEC2");
  return b;
}

TEST(GltfLoader, TextureTransformMapsTheUvsAsTheExtensionDefines) {
  fs::path dir = test::temp_dir();
  write_png(dir / "tex.png", 1, 1, 8, 2, {1, 2, 3});
  GltfBuilder b = triangle_with_two_uv_sets();
  b.doc["extensionsRequired"] = {"KHR_texture_transform"};
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  auto& info = b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
  // Scale, then rotate by 90 degrees (u' = v, v' = -u), then offset.
  info["extensions"]["KHR_texture_transform"] = {{"offset", {0.25, 0.5}}, {"rotation", M_PI / 2}, {"scale", {2.0, 3.0}}};
  Scene s = load_gltf(b.write(dir, "transformed").string());
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_FALSE(has_warning(s, "KHR_texture_transform"));
  EXPECT_FALSE(has_warning(s, "UV"));
  // (1,0) -> scaled (2,0) -> rotated (0,-2) -> (0.25,-1.5); (0,1) -> (0,3) -> (3,0) -> (3.25,0.5).
  EXPECT_NEAR(s.uvs[s.triangles[0].x].x, 0.25f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].x].y, 0.5f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].y].x, 0.25f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].y].y, -1.5f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].z].x, 3.25f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].z].y, 0.5f, 1e-6f);
  EXPECT_EQ(s.gltf_features, std::vector<std::string>{"KHR_texture_transform"});
  // The extension's texCoord overrides the texture's.
  info["extensions"]["KHR_texture_transform"] = {{"texCoord", 1}};
  Scene second = load_gltf(b.write(dir, "second").string());
  EXPECT_NEAR(second.uvs[second.triangles[0].y].x, 1.0f, 1e-6f);
  EXPECT_NEAR(second.uvs[second.triangles[0].y].y, 0.5f, 1e-6f);
  EXPECT_EQ(second.gltf_features, std::vector<std::string>{"TEXCOORD_1"});
  info["extensions"]["KHR_texture_transform"] = {{"texCoord", 1e300}};
  fs::path huge = b.write(dir, "huge");
  expect_one_line_naming(load_error(huge), huge, "material 0 baseColorTexture has a texCoord that is not a whole number in 0..7");
  info["extensions"]["KHR_texture_transform"] = {{"scale", {1.0}}};
  fs::path bad = b.write(dir, "bad");
  expect_one_line_naming(load_error(bad), bad, "material 0 baseColorTexture has a KHR_texture_transform scale that is not 2 numbers");
}

TEST(GltfLoader, TexCoordSelectsTheUvSetAndAMissingSetIsAnError) {
  fs::path dir = test::temp_dir();
  write_png(dir / "tex.png", 1, 1, 8, 2, {1, 2, 3});
  GltfBuilder b = triangle_with_two_uv_sets();
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
  Scene s = load_gltf(b.write(dir, "set1").string());
  EXPECT_NEAR(s.uvs[s.triangles[0].z].x, 0.5f, 1e-6f);
  EXPECT_NEAR(s.uvs[s.triangles[0].z].y, 1.0f, 1e-6f);
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 2;
  fs::path p = b.write(dir, "set2");
  expect_one_line_naming(load_error(p), p, "has no TEXCOORD_2, which its material's textures use");
  // Textures of one material that disagree keep the baseColorTexture's, with a warning.
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
  b.doc["materials"][0]["emissiveTexture"] = {{"index", 0}, {"texCoord", 0}};
  Scene mixed = load_gltf(b.write(dir, "mixed").string());
  EXPECT_NEAR(mixed.uvs[mixed.triangles[0].z].x, 0.5f, 1e-6f);
  EXPECT_TRUE(has_warning(mixed, "different UV sets or transforms"));
}

TEST(GltfLoader, AlphaModesNormalMapsAndOcclusion) {
  fs::path dir = test::temp_dir();
  write_png(dir / "tex.png", 1, 1, 8, 2, {1, 2, 3});
  GltfBuilder b = textured_triangle("tex.png");
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, 0.25};
  b.doc["materials"][0]["alphaMode"] = "MASK";
  b.doc["materials"][0]["alphaCutoff"] = 0.125;
  b.doc["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", 0.5}};
  b.doc["materials"][0]["occlusionTexture"] = {{"index", 0}};
  Scene s = load_gltf(b.write(dir, "mask").string());
  const Material& m = s.materials[0];
  EXPECT_EQ(m.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alpha, 0.25f);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.125f);
  EXPECT_EQ(m.normal_texture, 1);  // the same image as the base colour, read linear: a texture of its own
  EXPECT_EQ(s.textures.size(), 2u);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_TRUE(has_warning(s, "occlusion textures are ignored"));
  EXPECT_EQ(s.gltf_features, (std::vector<std::string>{"alphaMode MASK", "normalTexture"}));

  b.doc["materials"][0]["alphaMode"] = "BLEND";
  Scene blend = load_gltf(b.write(dir, "blend").string());
  EXPECT_EQ(blend.materials[0].alpha_mode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(material_alpha_cutoff(blend.materials[0]), 0.5f);

  b.doc["materials"][0]["alphaMode"] = "CUTOUT";
  fs::path bad = b.write(dir, "bad");
  expect_one_line_naming(load_error(bad), bad, "has alphaMode 'CUTOUT' (must be OPAQUE, MASK or BLEND)");
  b.doc["materials"][0]["alphaMode"] = "MASK";
  b.doc["materials"][0]["alphaCutoff"] = -1;
  fs::path negative = b.write(dir, "negative");
  expect_one_line_naming(load_error(negative), negative, "has alphaCutoff");
}

TEST(GltfLoader, VertexColorsAndTangentsAreLoadedAndTransformed) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  const std::vector<uint8_t> rgba = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0};  // normalized bytes
  const int colors = b.accessor(b.view(rgba), kByte, 3, "VEC4", 0, true);
  const std::vector<float> tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, -1};
  const int tan = b.accessor(b.view(tangents), kFloat, 3, "VEC4");
  json prim = {{"attributes",
                {{"POSITION", b.vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0})},
                 {"NORMAL", b.vec3s({0, 0, 1, 0, 0, 1, 0, 0, 1})},
                 {"COLOR_0", colors},
                 {"TANGENT", tan}}}};
  const int with = b.mesh(prim);
  const int plain = b.triangle_mesh();
  // The first node mirrors x: the tangent turns to -x, and w flips with the winding.
  b.scene({b.node({{"mesh", with}, {"scale", {-2, 1, 1}}}), b.node({{"mesh", plain}, {"translation", {0, 0, 5}}})});
  Scene s = load_gltf(b.write(dir, "colors").string());
  ASSERT_EQ(s.positions.size(), 6u);
  ASSERT_EQ(s.colors.size(), 6u);
  ASSERT_EQ(s.tangents.size(), 6u);
  // Vertex order follows the (mirrored, so swapped) triangle's first use: find vertices by position.
  for (size_t i = 0; i < 3; ++i) {
    const vec3 p = s.positions[i];
    const int k = p.x < -0.5f ? 1 : p.y > 0.5f ? 2 : 0;
    const vec4 want = vec4(rgba[4 * k], rgba[4 * k + 1], rgba[4 * k + 2], rgba[4 * k + 3]) / 255.0f;
    EXPECT_EQ(s.colors[i], want) << i;
    EXPECT_EQ(vec3(s.tangents[i]), vec3(-1, 0, 0)) << i;
    EXPECT_EQ(s.tangents[i].w, tangents[4 * k + 3] < 0 ? 1.0f : -1.0f) << i;
  }
  for (size_t i = 3; i < 6; ++i) {
    EXPECT_EQ(s.colors[i], vec4(1.0f)) << "a primitive without COLOR_0 is white";
    EXPECT_EQ(s.tangents[i], vec4(0.0f)) << "a primitive without TANGENT derives it";
  }
  EXPECT_EQ(s.gltf_features, (std::vector<std::string>{"COLOR_0", "TANGENT"}));
}

// ---- lights and cameras ----

TEST(GltfLoader, PunctualLightsFromNodes) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
      {{{"name", "bulb"}, {"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 4.0}, {"range", 10.0}},
       {{"name", "cone"}, {"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
       {{"type", "spot"}, {"spot", json::object()}},
       {{"name", "sun"}, {"type", "directional"}, {"intensity", 3.0}}});
  const float s = std::sqrt(0.5f);
  auto light = [](int i) { return json{{"KHR_lights_punctual", {{"light", i}}}}; };
  b.scene({b.node({{"mesh", b.triangle_mesh()}}),
           b.node({{"translation", {1, 2, 3}}, {"extensions", light(0)}}),
           b.node({{"translation", {0, 5, 0}}, {"extensions", light(1)}}),
           b.node({{"name", "default-cone"}, {"extensions", light(2)}}),
           b.node({{"rotation", {s, 0, 0, s}}, {"extensions", light(3)}})});  // 90 deg about X
  Scene sc = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(sc.lights.size(), 4u);
  const PunctualLight& bulb = sc.lights[0];
  EXPECT_EQ(bulb.type, LightType::Point);
  expect_near(bulb.position, vec3(1, 2, 3));
  expect_near(bulb.intensity, vec3(4.0f, 2.0f, 1.0f));
  EXPECT_TRUE(has_warning(sc, "range ignored"));
  const PunctualLight& cone = sc.lights[1];
  EXPECT_EQ(cone.type, LightType::Spot);
  EXPECT_NEAR(cone.cos_inner, std::cos(0.2f), 1e-6f);
  EXPECT_NEAR(cone.cos_outer, std::cos(0.5f), 1e-6f);
  expect_near(cone.direction, vec3(0, 0, -1));
  EXPECT_EQ(sc.lights[2].name, "default-cone");
  EXPECT_NEAR(sc.lights[2].cos_inner, 1.0f, 1e-6f);
  EXPECT_NEAR(sc.lights[2].cos_outer, std::cos(kPi / 4), 1e-6f);
  const PunctualLight& sun = sc.lights[3];
  EXPECT_EQ(sun.type, LightType::Directional);
  expect_near(sun.direction, vec3(0, 1, 0));  // -Z turned 90 deg about X points up
  expect_near(sun.intensity, vec3(3.0f));
}

TEST(GltfLoader, CameraFromNode) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"aspectRatio", 1.5}, {"znear", 0.1}}}},
                                  {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                                  {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}});
  const float s = std::sqrt(0.5f);
  b.scene({b.node({{"mesh", b.triangle_mesh()}}),
           b.node({{"name", "side"}, {"camera", 0}, {"translation", {0, 1, 5}}, {"rotation", {0, s, 0, s}}}),  // 90 deg about Y
           b.node({{"name", "plain"}, {"camera", 1}}),
           b.node({{"name", "ortho"}, {"camera", 2}})});
  Scene sc = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(sc.cameras.size(), 2u);
  const Camera& c = sc.cameras[0];
  EXPECT_EQ(c.name, "side");
  expect_near(c.eye, vec3(0, 1, 5));
  expect_near(c.forward, vec3(-1, 0, 0));
  expect_near(c.up, vec3(0, 1, 0));
  EXPECT_NEAR(c.yfov, 0.7f, 1e-6f);
  EXPECT_NEAR(c.aspect, 1.5f, 1e-6f);
  EXPECT_EQ(sc.cameras[1].name, "plain");
  EXPECT_EQ(sc.cameras[1].aspect, 0.0f);
  EXPECT_TRUE(has_warning(sc, "orthographic"));
}

TEST(GltfLoader, AutoCameraFramesTheBoundsAndNoLightsIsAWarning) {
  fs::path dir = test::temp_dir();
  GltfBuilder b;
  int pos = b.vec3s({-1, -2, -3, 4, -2, -3, -1, 5, 6});
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}})}})});
  Scene s = load_gltf(b.write(dir, "scene").string());
  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, "auto");
  expect_near(c.forward, vec3(0, 0, -1));
  expect_near(c.up, vec3(0, 1, 0));
  EXPECT_NEAR(c.yfov, 0.8f, 1e-6f);
  EXPECT_GT(c.eye.z, s.bounds.hi.z);
  // Every corner of the box lies inside the vertical and (square) horizontal field of view.
  float t = std::tan(0.5f * c.yfov);
  for (int i = 0; i < 8; ++i) {
    vec3 corner((i & 1) ? s.bounds.hi.x : s.bounds.lo.x, (i & 2) ? s.bounds.hi.y : s.bounds.lo.y,
                (i & 4) ? s.bounds.hi.z : s.bounds.lo.z);
    vec3 d = corner - c.eye;
    float depth = -d.z;
    ASSERT_GT(depth, 0.0f);
    EXPECT_LE(std::abs(d.y) / depth, t);
    EXPECT_LE(std::abs(d.x) / depth, t);
  }
  EXPECT_TRUE(has_warning(s, "auto"));
  EXPECT_TRUE(has_warning(s, "scene has no lights: the image will be black"));
}

// ---- the shared scenes, when present beside the checkout ----

void expect_shared_scene_loads(const std::string& name) {
  fs::path gltf = test::shared_scene(name + "/" + name + ".gltf");
  fs::path manifest = test::shared_scene("MANIFEST.json");
  if (gltf.empty() || manifest.empty()) GTEST_SKIP() << "shared scenes not present";
  size_t expected = json::parse(std::ifstream(manifest))["scenes"][name]["triangles"].get<size_t>();
  auto start = std::chrono::steady_clock::now();
  Scene s = load_gltf(gltf.string());
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ timing   ] %s: %zu triangles, %zu textures, loaded in %.3f s\n", name.c_str(), s.triangles.size(),
              s.textures.size(), seconds);
  // MANIFEST counts the file's triangles; the loader drops the zero-area ones and says how many.
  size_t dropped = 0;
  for (const std::string& w : s.warnings) std::sscanf(w.c_str(), "dropped %zu zero-area triangles", &dropped);
  EXPECT_EQ(s.triangles.size() + dropped, expected);
  EXPECT_LT(dropped, expected / 20);
  ASSERT_FALSE(s.cameras.empty());
  EXPECT_EQ(s.cameras[0].name, "main");
  for (const std::string& w : s.warnings) std::printf("[ warning  ] %s\n", w.c_str());
}

TEST(GltfLoader, SharedStaircaseLoads) { expect_shared_scene_loads("staircase"); }
TEST(GltfLoader, SharedBreakfastRoomLoads) { expect_shared_scene_loads("breakfast-room"); }
TEST(GltfLoader, SharedLivingRoomLoads) { expect_shared_scene_loads("living-room-2"); }

TEST(GltfLoader, SharedCornellPointVariantHasItsPointLight) {
  fs::path gltf = test::shared_scene("cornell-box/cornell-box-point.gltf");
  if (gltf.empty()) GTEST_SKIP() << "shared scenes not present";
  Scene s = load_gltf(gltf.string());
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  expect_near(s.lights[0].position, vec3(0.0f, 1.4f, 0.3f));
  expect_near(s.lights[0].intensity, vec3(2.0f));
}

}  // namespace
}  // namespace sst
