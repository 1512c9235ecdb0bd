// The scene on the GPU (gpu/scene_upload.h, core/scene/scene_layout.h, gpu/shaders/surface.glsl):
// pack_scene's invariants without a device, then make_surface (core/shading/surface_eval.h)
// compiled as GLSL against the same source compiled as C++ on hits found by Embree. The GPU parts skip where there is no device;
// everything is compiled only when the Vulkan backend is (SST_HAVE_VULKAN: gpu/*.cpp exist only
// then).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cmath>
#include <cstdio>
#include <bit>
#include <memory>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/image/image.h"
#include "core/pipeline/backend.h"
#include "core/shading/surface.h"
#include "core/rng/hash_rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/util/error.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/scene_upload.h"
#include "gpu/shader_library.h"
#include "gpu/vulkan_context.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst::gpu {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }
float from_bits(uint32_t b) { return std::bit_cast<float>(b); }

const Scene& cornell_box() {
  static const Scene scene = load_default_scene();
  return scene;
}

// The staircase of the shared scenes (textured), loaded once; nullptr when absent.
const Scene* staircase() {
  static const Scene* scene = []() -> const Scene* {
    auto path = test::shared_scene("staircase/staircase.gltf");
    if (path.empty()) return nullptr;
    return new Scene(load_gltf(path.string()));
  }();
  return scene;
}

void check_packing(const Scene& scene, const PackedScene& packed) {
  ASSERT_EQ(packed.vertices.size(), scene.positions.size());
  ASSERT_EQ(packed.triangles.size(), scene.triangles.size());
  ASSERT_EQ(packed.materials.size(), scene.materials.size());
  ASSERT_EQ(packed.textures.size(), scene.textures.size());
  for (size_t i = 0; i < packed.vertices.size(); ++i) {
    const glsl::SceneVertex& v = packed.vertices[i];
    ASSERT_EQ(v.position, scene.positions[i]) << i;
    ASSERT_EQ(v.normal, scene.normals[i]) << i;
    vec2 uv = scene.uvs.empty() ? vec2(0.0f) : scene.uvs[i];
    ASSERT_EQ(bits(v.u), bits(uv.x)) << i;
    ASSERT_EQ(bits(v.v), bits(uv.y)) << i;
    ASSERT_EQ(v.tangent, scene.tangents.empty() ? vec4(0.0f) : scene.tangents[i]) << i;
    ASSERT_EQ(v.color, scene.colors.empty() ? vec4(1.0f) : scene.colors[i]) << i;
  }
  const uint32_t nv = uint32_t(packed.vertices.size()), nm = uint32_t(packed.materials.size());
  for (size_t i = 0; i < packed.triangles.size(); ++i) {
    const glsl::SceneTriangle& t = packed.triangles[i];
    ASSERT_TRUE(t.v0 < nv && t.v1 < nv && t.v2 < nv && t.material < nm) << "triangle " << i;
    ASSERT_EQ(uvec3(t.v0, t.v1, t.v2), scene.triangles[i]);
    ASSERT_EQ(t.material, scene.triangle_material[i]);
  }
  const int nt = int(packed.textures.size());
  for (size_t i = 0; i < packed.materials.size(); ++i) {
    const glsl::SceneMaterial& g = packed.materials[i];
    const Material& m = scene.materials[i];
    EXPECT_EQ(g.base_color, m.base_color);
    EXPECT_EQ(g.emission, m.emission);
    EXPECT_EQ(g.metallic, m.metallic);
    EXPECT_EQ(g.roughness, m.roughness);
    EXPECT_EQ(g.double_sided, m.double_sided ? 1u : 0u);
    EXPECT_EQ(g.alpha, m.alpha);
    EXPECT_EQ(g.alpha_cutoff, m.alpha_mode == AlphaMode::Opaque ? 0.0f : m.alpha_mode == AlphaMode::Blend ? 0.5f : m.alpha_cutoff);
    EXPECT_EQ(g.normal_texture, m.normal_texture < nt ? m.normal_texture : -1);
    EXPECT_EQ(g.normal_scale, m.normal_scale);
    for (int tex : {g.base_color_texture, g.metallic_roughness_texture, g.emissive_texture})
      EXPECT_TRUE(tex == -1 || (tex >= 0 && tex < nt)) << "material " << i << " texture " << tex;
    EXPECT_EQ(g.base_color_texture, m.base_color_texture < nt ? m.base_color_texture : -1);
    EXPECT_EQ(g.emissive_texture, m.emissive_texture < nt ? m.emissive_texture : -1);
  }
  // The decoding tables, then the textures tiling the texel array in order, without gaps or
  // overlaps, with the CPU's texels.
  ASSERT_GE(packed.texels.size(), size_t(SCENE_TEXELS_FIRST_TEXEL));
  for (uint32_t i = 0; i < 256; ++i) {
    ASSERT_EQ(packed.texels[SCENE_TEXELS_SRGB_TABLE + i], glsl::scene_srgb_decode_bits[i]);
    ASSERT_EQ(packed.texels[SCENE_TEXELS_UNORM8_TABLE + i], glsl::scene_unorm8_bits[i]);
  }
  size_t next = SCENE_TEXELS_FIRST_TEXEL;
  for (size_t i = 0; i < packed.textures.size(); ++i) {
    const glsl::SceneTexture& g = packed.textures[i];
    const Texture& t = scene.textures[i];
    EXPECT_EQ(g.texel_offset, next) << "texture " << i;
    EXPECT_EQ(g.width, t.width);
    EXPECT_EQ(g.height, t.height);
    EXPECT_LE(g.format, SCENE_TEXTURE_RGBA32F);
    EXPECT_LE(g.wrap_s, SCENE_WRAP_MIRRORED_REPEAT);
    EXPECT_LE(g.wrap_t, SCENE_WRAP_MIRRORED_REPEAT);
    const size_t count = size_t(g.width) * size_t(g.height);
    const size_t words = g.format == SCENE_TEXTURE_RGBA32F ? 4 * count : count;
    ASSERT_LE(g.texel_offset + words, packed.texels.size()) << "texture " << i;
    for (size_t k = 0; k < count; k += std::max<size_t>(1, count / 97)) {
      if (g.format == SCENE_TEXTURE_RGBA32F) {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(packed.texels[g.texel_offset + 4 * k + c], bits(t.texels[k][c]));
      } else {
        ASSERT_EQ(packed.texels[g.texel_offset + k], t.rgba8[k]);
        EXPECT_EQ(g.format == SCENE_TEXTURE_RGBA8_SRGB, t.srgb);
      }
    }
    next = g.texel_offset + words;
  }
  EXPECT_EQ(next, packed.texels.size());
  EXPECT_EQ(packed.bytes(), packed.vertices.size() * 64 + packed.triangles.size() * 16 +
                                packed.materials.size() * 64 + packed.textures.size() * 32 + packed.texels.size() * 4);
}

TEST(SceneUpload, DecodingTablesAreTheCppOnes) {
  for (int i = 0; i < 256; ++i) {
    ASSERT_EQ(glsl::scene_srgb_decode_bits[i], bits(srgb_decode(float(i) / 255.0f))) << i;
    ASSERT_EQ(glsl::scene_unorm8_bits[i], bits(float(i) / 255.0f)) << i;
  }
  EXPECT_EQ(SCENE_INV_255_BITS, bits(1.0f / 255.0f));
  // And the texture code decodes through the same values.
  Texture t;
  t.width = 256;
  t.height = 1;
  for (uint32_t i = 0; i < 256; ++i) t.rgba8.push_back(i | (i << 8) | ((255 - i) << 16) | (i << 24));
  for (bool srgb : {false, true}) {
    t.srgb = srgb;
    for (uint32_t i = 0; i < 256; ++i) {
      vec4 c = t.texel(i);
      uint32_t expected = srgb ? glsl::scene_srgb_decode_bits[i] : bits(float(i) * from_bits(SCENE_INV_255_BITS));
      EXPECT_EQ(bits(c.x), expected) << i;
      EXPECT_EQ(bits(c.w), glsl::scene_unorm8_bits[i]) << i;
    }
  }
}

TEST(SceneUpload, CornellBoxPacksIndexForIndex) {
  const Scene& scene = cornell_box();
  PackedScene packed = pack_scene(scene);
  check_packing(scene, packed);
  EXPECT_GT(packed.triangles.size(), 0u);
  std::printf("%s\n", describe(packed).c_str());
}

TEST(SceneUpload, TexturedStaircasePacksIndexForIndex) {
  const Scene* scene = staircase();
  if (!scene) GTEST_SKIP() << "shared scene staircase/staircase.gltf not present";
  PackedScene packed = pack_scene(*scene);
  check_packing(*scene, packed);
  EXPECT_GT(packed.textures.size(), 0u);
  EXPECT_GT(packed.texels.size(), 0u);
  std::printf("%s\n", describe(packed).c_str());
}

TEST(SceneUpload, OutOfRangeIndicesAreErrorsOrAbsentTextures) {
  Scene scene = cornell_box();
  scene.materials[0].base_color_texture = 7;  // no texture 7: the CPU samples it as 1, so -1
  scene.materials[0].emissive_texture = -5;
  PackedScene packed = pack_scene(scene);
  EXPECT_EQ(packed.materials[0].base_color_texture, -1);
  EXPECT_EQ(packed.materials[0].emissive_texture, -1);

  Scene bad = cornell_box();
  bad.triangles[3].y = uint32_t(bad.positions.size());
  EXPECT_THROW(pack_scene(bad), Error);
  bad = cornell_box();
  bad.triangle_material[2] = uint32_t(bad.materials.size());
  EXPECT_THROW(pack_scene(bad), Error);
  bad = cornell_box();
  bad.normals.pop_back();
  EXPECT_THROW(pack_scene(bad), Error);
  bad = cornell_box();
  Texture small;
  small.width = small.height = 4;
  small.rgba8.assign(15, 0u);
  bad.textures.push_back(small);
  EXPECT_THROW(pack_scene(bad), Error);
}

// ---- CPU make_surface against the shader -------------------------------------------------------

struct Query {
  uint32_t triangle;
  vec2 b;
  vec3 incoming;
};

struct Differences {
  double position_rel = 0, ng = 0, ns = 0, uv = 0, base_color = 0, emission = 0, metallic_roughness = 0;
  size_t exact_texture_values = 0, texture_values = 0, exact_normals = 0, count = 0;
};

// Evaluates every query with make_surface on the CPU and surface_test.comp on the GPU, checks the
// tolerances and returns the largest differences.
Differences compare_surfaces(const Scene& scene, const std::vector<Query>& queries) {
  Differences d;
  VulkanContext context(0);
  GpuScene gpu_scene(context, scene);
  EXPECT_EQ(gpu_scene.triangle_count(), scene.triangles.size());
  EXPECT_GE(gpu_scene.bytes(), pack_scene(scene).bytes());

  const uint32_t count = uint32_t(queries.size());
  std::vector<uint32_t> in(size_t(count) * 8, 0u);
  for (uint32_t i = 0; i < count; ++i) {
    const Query& q = queries[i];
    uint32_t* w = &in[size_t(i) * 8];
    w[0] = q.triangle;
    w[1] = bits(q.b.x);
    w[2] = bits(q.b.y);
    w[4] = bits(q.incoming.x);
    w[5] = bits(q.incoming.y);
    w[6] = bits(q.incoming.z);
  }
  GpuBuffer query_buffer(context, in.size() * 4), result_buffer(context, size_t(count) * 24 * 4);
  query_buffer.upload(std::span<const uint32_t>(in));
  ComputePipeline pipeline(context, "surface_test", GpuScene::kBufferCount + 2, 4);
  std::vector<const GpuBuffer*> buffers = gpu_scene.buffers();
  buffers.push_back(&query_buffer);
  buffers.push_back(&result_buffer);
  const double ms = pipeline.dispatch(buffers, &count, (count + 63) / 64);
  std::vector<uint32_t> out(size_t(count) * 24);
  result_buffer.download(std::span<uint32_t>(out));

  auto v3 = [&](size_t o) { return vec3(from_bits(out[o]), from_bits(out[o + 1]), from_bits(out[o + 2])); };
  auto maxdiff = [](vec3 a, vec3 b) { return double(max_component(glm::abs(a - b))); };
  int failures = 0;
  for (uint32_t i = 0; i < count && failures < 10; ++i) {
    const Query& q = queries[i];
    Hit hit;
    hit.triangle = q.triangle;
    hit.barycentric = q.b;
    hit.t = 1.0f;
    const Surface s = make_surface(scene, hit, q.incoming);
    const size_t o = size_t(i) * 24;
    const vec3 p = v3(o), ng = v3(o + 4), ns = v3(o + 8), base = v3(o + 16), emission = v3(o + 20);
    const vec2 uv(from_bits(out[o + 12]), from_bits(out[o + 13]));
    const float metallic = from_bits(out[o + 14]), roughness = from_bits(out[o + 15]);
    const double prel = maxdiff(p, s.p) / std::max(1e-6, double(max_component(glm::abs(s.p))));
    const double dng = maxdiff(ng, s.ng), dns = maxdiff(ns, s.ns);
    const double duv = std::max(std::abs(double(uv.x) - s.uv.x), std::abs(double(uv.y) - s.uv.y));
    const double dbase = maxdiff(base, s.base_color), demission = maxdiff(emission, s.emission);
    const double dmr = std::max(std::abs(double(metallic) - s.metallic), std::abs(double(roughness) - s.roughness));
    d.position_rel = std::max(d.position_rel, prel);
    d.ng = std::max(d.ng, dng);
    d.ns = std::max(d.ns, dns);
    d.uv = std::max(d.uv, duv);
    d.base_color = std::max(d.base_color, dbase);
    d.emission = std::max(d.emission, demission);
    d.metallic_roughness = std::max(d.metallic_roughness, dmr);
    d.exact_normals += ng == s.ng && ns == s.ns;
    for (int c = 0; c < 3; ++c) d.exact_texture_values += (bits(base[c]) == bits(s.base_color[c])) + (bits(emission[c]) == bits(s.emission[c]));
    d.exact_texture_values += (bits(metallic) == bits(s.metallic)) + (bits(roughness) == bits(s.roughness));
    d.texture_values += 8;
    ++d.count;
    const bool ok = (out[o + 3] != 0u) == s.front_face && out[o + 7] == s.material && out[o + 11] == s.triangle &&
                    prel <= 1e-5 && dng <= 1e-5 && dns <= 1e-5 && duv <= 1e-5 && dbase <= 1e-5 &&
                    demission <= 1e-5 && dmr <= 1e-5;
    if (!ok) {
      ++failures;
      ADD_FAILURE() << "query " << i << " triangle " << q.triangle << " b (" << q.b.x << ", " << q.b.y
                    << "): front_face gpu " << out[o + 3] << " cpu " << s.front_face << ", material gpu "
                    << out[o + 7] << " cpu " << s.material << ", |dp|/|p| " << prel << ", ng " << dng << ", ns "
                    << dns << ", uv " << duv << ", base_color " << dbase << ", emission " << demission
                    << ", metallic/roughness " << dmr;
    }
  }
  std::printf("%s; %zu surfaces: max |dp|/|p| %.3g, |d ng| %.3g, |d ns| %.3g, |d uv| %.3g, |d base_color| %.3g, "
              "|d emission| %.3g, |d metallic/roughness| %.3g; bit-identical: %zu/%zu texture-derived values, "
              "%zu/%zu normal pairs; GPU %.2f ms\n",
              describe(pack_scene(scene)).c_str(), d.count, d.position_rel, d.ng, d.ns, d.uv, d.base_color,
              d.emission, d.metallic_roughness, d.exact_texture_values, d.texture_values, d.exact_normals, d.count, ms);
  return d;
}

// Hits of random rays, fixed seed: half from camera-like eyes (the scene's camera, else outside
// the bounds looking at the centre) into a cone, half from random points inside the bounds in
// random directions (so that back faces and grazing angles are seen too).
std::vector<Query> traced_queries(const Scene& scene, uint32_t wanted) {
  EmbreeAccel accel(scene);
  std::vector<Query> queries;
  const vec3 lo = scene.bounds.lo, hi = scene.bounds.hi, centre = scene.bounds.center();
  vec3 eye = centre + vec3(0.0f, 0.0f, 1.5f * scene.bounds.diagonal()), forward = glm::normalize(centre - eye);
  if (!scene.cameras.empty()) {
    eye = scene.cameras[0].eye;
    forward = scene.cameras[0].forward;
  }
  const auto [t1, t2] = [&] {
    vec3 a = std::abs(forward.x) > 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
    vec3 u = glm::normalize(glm::cross(forward, a));
    return std::pair{u, glm::cross(forward, u)};
  }();
  for (uint32_t i = 0; queries.size() < wanted && i < 20 * wanted; ++i) {
    HashRng rng = hash_rng(2024u, i, 0u);
    Ray ray;
    if (i % 2 == 0) {
      ray.origin = eye;
      float x = 2.0f * hash_rng_next(rng) - 1.0f, y = 2.0f * hash_rng_next(rng) - 1.0f;
      ray.direction = glm::normalize(forward + 0.7f * x * t1 + 0.7f * y * t2);
    } else {
      ray.origin = lo + vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng)) * (hi - lo);
      ray.direction = sample_uniform_sphere(hash_rng_next(rng), hash_rng_next(rng));
    }
    Hit hit = accel.intersect(ray);
    if (hit.valid()) queries.push_back({hit.triangle, hit.barycentric, ray.direction});
  }
  return queries;
}

TEST(GpuScene, UploadsEveryArrayAndReportsItsSize) {
  SKIP_WITHOUT_GPU("surface_test");
  VulkanContext context(0);
  const Scene& scene = staircase() ? *staircase() : cornell_box();
  PackedScene packed = pack_scene(scene);
  GpuScene gpu(context, packed);
  EXPECT_EQ(gpu.vertex_count(), packed.vertices.size());
  EXPECT_EQ(gpu.triangle_count(), packed.triangles.size());
  EXPECT_EQ(gpu.material_count(), packed.materials.size());
  EXPECT_EQ(gpu.texture_count(), packed.textures.size());
  EXPECT_EQ(gpu.texel_words(), packed.texels.size());
  ASSERT_EQ(gpu.buffers().size(), size_t(GpuScene::kBufferCount));
  EXPECT_EQ(gpu.vertices().size(), packed.vertices.size() * sizeof(glsl::SceneVertex));
  EXPECT_EQ(gpu.texels().size(), packed.texels.size() * 4);
  EXPECT_GE(gpu.bytes(), packed.bytes());
  EXPECT_LE(gpu.bytes(), packed.bytes() + 5 * 16);
  std::vector<glsl::SceneTriangle> back(packed.triangles.size());
  gpu.triangles().download(std::span<glsl::SceneTriangle>(back));
  EXPECT_EQ(std::memcmp(back.data(), packed.triangles.data(), back.size() * sizeof(back[0])), 0);
  std::printf("%s on %s: %zu bytes of device memory\n", describe(packed).c_str(), context.info().name.c_str(),
              gpu.bytes());
}

void check_traced_hits(const Scene& scene) {
  std::vector<Query> queries = traced_queries(scene, 4000);
  ASSERT_GT(queries.size(), 1000u);
  size_t back = 0;
  for (const Query& q : queries)
    back += glm::dot(triangle_geometric_normal(scene, q.triangle), q.incoming) >= 0.0f;
  EXPECT_GT(back, 0u) << "no back-face hits among the queries";
  Differences d = compare_surfaces(scene, queries);
  // Texture lookups use only correctly rounded operations in the C++ order: the same bits.
  EXPECT_EQ(d.exact_texture_values, d.texture_values) << "texture lookups are not bit-identical";
}

// The Cornell box always, and the textured staircase when the shared scenes are present.
TEST(GpuScene, SurfacesAtTracedHitsMatchTheCpu) {
  SKIP_WITHOUT_GPU("surface_test");
  check_traced_hits(cornell_box());
  if (staircase()) check_traced_hits(*staircase());
  else std::printf("shared scene staircase/staircase.gltf not present: Cornell box only\n");
}

// Every texture mode the loader can produce, on a generated scene: 8-bit linear and sRGB, float
// texels, repeat / clamp / mirrored wraps, nearest, uvs far outside [0, 1], emissive textures,
// one- and double-sided emitters; queries at random barycentrics (some outside the triangle, as
// Embree's edges give) from both sides.
TEST(GpuScene, EveryTextureModeMatchesTheCpu) {
  SKIP_WITHOUT_GPU("surface_test");
  Scene scene;
  scene.source = "generated:texture-modes";
  const Wrap wraps[3] = {Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat};
  for (int k = 0; k < 9; ++k) {
    Texture t;
    t.width = 3 + k;
    t.height = 5 + 2 * k;
    t.wrap_s = wraps[k % 3];
    t.wrap_t = wraps[(k / 3) % 3];
    t.nearest = k == 4 || k == 8;
    const bool is_float = k == 2 || k == 7;
    t.srgb = k % 2 == 0;
    for (int i = 0; i < t.width * t.height; ++i) {
      uint32_t h = pcg_hash(uint32_t(k * 1000 + i));
      if (is_float) t.texels.push_back(vec4(float(h & 0xFFF) / 300.0f, float((h >> 12) & 0xFF) / 7.0f, 0.25f, 1.0f));
      else t.rgba8.push_back(h);
    }
    scene.textures.push_back(std::move(t));
  }
  scene.textures.push_back(Texture{});  // empty: samples as 1
  for (int k = 0; k < 12; ++k) {
    Material m;
    m.base_color = vec3(0.9f, 0.5f + 0.01f * k, 0.3f);
    m.metallic = 0.7f;
    m.roughness = 0.3f + 0.05f * k;
    m.base_color_texture = k < 10 ? k : (k == 10 ? 42 : -1);
    m.metallic_roughness_texture = (k + 3) % 10;
    m.emission = k % 3 == 0 ? vec3(2.0f, 1.5f, 0.5f) : vec3(0.0f);
    m.emissive_texture = k % 3 == 0 ? (k + 5) % 10 : -1;
    m.double_sided = k % 2 == 1;
    scene.materials.push_back(m);
  }
  for (int k = 0; k < 12; ++k) {
    uint32_t base = uint32_t(scene.positions.size());
    vec3 o(float(k), 0.5f * k, -1.0f);
    scene.positions.insert(scene.positions.end(), {o, o + vec3(1.3f, 0.1f, 0.0f), o + vec3(0.2f, 0.9f, 0.3f)});
    scene.normals.insert(scene.normals.end(), {glm::normalize(vec3(0.1f, 0, 1)), vec3(0, 0, 1), glm::normalize(vec3(-0.3f, 0.2f, -1))});
    scene.uvs.insert(scene.uvs.end(), {vec2(-3.3f + k, 4.7f), vec2(5.1f, -2.6f - k), vec2(0.5f, 1e5f)});
    scene.triangles.push_back(uvec3(base, base + 1, base + 2));
    scene.triangle_material.push_back(uint32_t(k));
  }
  scene.finalize_bounds();
  std::vector<Query> queries;
  for (uint32_t i = 0; i < 6000; ++i) {
    HashRng rng = hash_rng(77u, i, 0u);
    float b1 = hash_rng_next(rng), b2 = hash_rng_next(rng);
    if (i % 7 != 0 && b1 + b2 > 1.0f) b1 = 1.0f - b1, b2 = 1.0f - b2;
    if (i % 11 == 0) b1 = -1e-3f * hash_rng_next(rng);
    queries.push_back({i % 12, vec2(b1, b2), sample_uniform_sphere(hash_rng_next(rng), hash_rng_next(rng))});
  }
  Differences d = compare_surfaces(scene, queries);
  EXPECT_EQ(d.exact_texture_values, d.texture_values) << "texture lookups are not bit-identical";
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
