// glTF scenes, generated in code, that each exercise one surface feature of the loader and the
// shared kernels (alpha masks, BLEND, COLOR_0, normal maps with and without TANGENT), with the
// image mean that theory predicts. Every scene is a floor (y = 0, 8 m square, Lambert albedo 0.5,
// metallic 0) seen from a camera straight above a point of it (square image, 60 degree field of
// view, image up = -z: narrow enough that no view is grazing to a bent normal), lit with max_bounces 0 by a directional light of irradiance pi (so that
// an unshadowed floor facing the light has radiance 0.5), or by an emitter.
//
// The masked screens carry a 2 x 2 checker of alpha 1 and 0 (NEAREST, REPEAT) whose cell corners
// meet under the camera. Rotating a checker by 90 degrees about a cell corner swaps its cells,
// and the camera's square view turns into itself, so each pixel has a partner whose light through
// the screen is the rest of the unmasked light: the expected image mean is exactly half the
// unmasked one, whatever the perspective and the kernel of the light.
#pragma once
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "tests/core/scene/gltf_test_files.h"

namespace sst::test {

struct FeatureScene {
  std::string name;
  fs::path path;
  vec3 expected{0.0f};  // image mean per channel (for `relative_to`, the ratio to that scene's)
  std::string relative_to;  // "": `expected` is absolute
  std::string what;          // what the scene checks, for the table
  bool reference = false;    // rendered only for another scene's `relative_to`: nothing expected
};

class FeatureSceneBuilder {
 public:
  explicit FeatureSceneBuilder(fs::path dir) : dir_(std::move(dir)) {
    write_png(dir_ / "checker.png", 2, 2, 8, 6, {255, 255, 255, 255, 255, 255, 255, 0,  //
                                                 255, 255, 255, 0, 255, 255, 255, 255});
  }

  // The floor (with the attributes `floor_extra` adds, and its u running along -x when
  // `floor_uv_mirrored`), a camera at height `camera_height` and, unless `light` is zero, a
  // directional light travelling along `light`.
  using Attributes = std::function<json(GltfBuilder&)>;
  GltfBuilder base(float camera_height, vec3 light, const json& floor_material, const Attributes& floor_extra = {},
                   bool floor_uv_mirrored = false, bool floor_draco = false) {
    GltfBuilder b;
    b.doc["extensionsUsed"] = json::array({"KHR_lights_punctual"});
    const int floor_mat = b.material(floor_material);
    std::vector<float> uv = {0, 0, 0, 1, 1, 1, 1, 0};
    if (floor_uv_mirrored)
      for (size_t i = 0; i < uv.size(); i += 2) uv[i] = 1.0f - uv[i];
    json attributes = {{"POSITION", b.vec3s({-4, 0, -4, -4, 0, 4, 4, 0, 4, 4, 0, -4})},
                       {"NORMAL", b.vec3s({0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0})},
                       {"TEXCOORD_0", b.accessor(b.view(uv), kFloat, 4, "VEC2")}};
    if (floor_extra) attributes.update(floor_extra(b));
    json floor = {{"attributes", attributes},
                  {"indices", b.indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUShort)},
                  {"material", floor_mat}};
    if (floor_draco) floor = draco_floor(b, uv, floor_mat);
    roots_ = {b.node({{"mesh", b.mesh(floor)}})};
    b.doc["cameras"] = json::array({{{"type", "perspective"},
                                     {"perspective", {{"yfov", M_PI / 3}, {"aspectRatio", 1.0}, {"znear", 0.01}}}}});
    roots_.push_back(b.node({{"camera", 0}, {"translation", {0, camera_height, 0}}, {"rotation", aim(vec3(0, -1, 0))}}));
    if (light != vec3(0.0f)) {
      b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
          json::array({{{"type", "directional"}, {"intensity", M_PI}}});
      roots_.push_back(b.node({{"rotation", aim(glm::normalize(light))},
                               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}));
    }
    return b;
  }

  // The floor as a KHR_draco_mesh_compression primitive (lossless: no quantization), its
  // accessors without bufferViews as the extension prescribes.
  static json draco_floor(GltfBuilder& b, const std::vector<float>& uv, int material) {
    const float p[4][3] = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
    const float n[3] = {0, 1, 0};
    const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    draco::TriangleSoupMeshBuilder mb;
    mb.Start(2);
    const int pos = mb.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nor = mb.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int tex = mb.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < 2; ++f) {
      const int* c = corners[f];
      mb.SetAttributeValuesForFace(pos, draco::FaceIndex(f), p[c[0]], p[c[1]], p[c[2]]);
      mb.SetAttributeValuesForFace(nor, draco::FaceIndex(f), n, n, n);
      mb.SetAttributeValuesForFace(tex, draco::FaceIndex(f), &uv[2 * c[0]], &uv[2 * c[1]], &uv[2 * c[2]]);
    }
    std::unique_ptr<draco::Mesh> mesh = mb.Finalize();
    draco::Encoder encoder;
    draco::EncoderBuffer buffer;
    if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) throw Error("draco encoding failed");
    const std::vector<char> bytes(buffer.data(), buffer.data() + buffer.size());
    const int view = b.view(bytes);
    auto bare = [&](int type, size_t count, const char* kind) {
      b.doc["accessors"].push_back({{"componentType", type}, {"count", count}, {"type", kind}});
      return int(b.doc["accessors"].size()) - 1;
    };
    const size_t points = mesh->num_points();
    json floor = {{"attributes",
                   {{"POSITION", bare(kFloat, points, "VEC3")},
                    {"NORMAL", bare(kFloat, points, "VEC3")},
                    {"TEXCOORD_0", bare(kFloat, points, "VEC2")}}},
                  {"indices", bare(kUShort, 6, "SCALAR")},
                  {"material", material}};
    floor["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", view},
        {"attributes",
         {{"POSITION", mesh->attribute(pos)->unique_id()},
          {"NORMAL", mesh->attribute(nor)->unique_id()},
          {"TEXCOORD_0", mesh->attribute(tex)->unique_id()}}}};
    b.doc["extensionsUsed"].push_back("KHR_draco_mesh_compression");
    b.doc["extensionsRequired"] = json::array({"KHR_draco_mesh_compression"});
    return floor;
  }

  // A 8 m square at height y facing `down` or up, uv 0..16 over it (32 checker cells), with
  // `material`.
  void add_screen(GltfBuilder& b, float y, bool facing_down, const json& material) {
    const int mat = b.material(material);
    std::vector<uint16_t> idx = facing_down ? std::vector<uint16_t>{0, 2, 1, 0, 3, 2} : std::vector<uint16_t>{0, 1, 2, 0, 2, 3};
    json screen = {{"attributes",
                    {{"POSITION", b.vec3s({-4, y, -4, -4, y, 4, 4, y, 4, 4, y, -4})},
                     {"TEXCOORD_0", b.accessor(b.view(std::vector<float>{0, 0, 0, 16, 16, 16, 16, 0}), kFloat, 4, "VEC2")}}},
                   {"indices", b.indices(idx, kUShort)},
                   {"material", mat}};
    roots_.push_back(b.node({{"mesh", b.mesh(screen)}}));
  }

  // The checker (alpha 1 and 0) as a base-colour texture with nearest filtering.
  static void add_checker_texture(GltfBuilder& b) {
    b.doc["images"] = json::array({{{"uri", "checker.png"}}});
    b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9728}}});  // NEAREST
    b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  }

  // A 1 x 1 linear texture holding one normal-map texel.
  void add_normal_texture(GltfBuilder& b, uint8_t r, uint8_t g, uint8_t bl) {
    const std::string file = "normal_" + std::to_string(r) + "_" + std::to_string(g) + "_" + std::to_string(bl) + ".png";
    write_png(dir_ / file, 1, 1, 8, 2, {r, g, bl});
    b.doc["images"] = json::array({{{"uri", file}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
  }

  fs::path write(GltfBuilder& b, const std::string& name) {
    b.scene(roots_);
    return b.write(dir_, name);
  }

  static json lambert(float albedo) {
    return {{"pbrMetallicRoughness", {{"baseColorFactor", {albedo, albedo, albedo, 1}}, {"metallicFactor", 0}}}};
  }

  // The node rotation (x, y, z, w) that turns glTF's view and light direction -z into `d`.
  static json aim(vec3 d) {
    glm::quat q = glm::rotation(vec3(0, 0, -1), d);
    if (d.y < -0.999f) q = glm::angleAxis(-float(M_PI) / 2, vec3(1, 0, 0));  // down, image up = -z
    return {q.x, q.y, q.z, q.w};
  }

 private:
  fs::path dir_;
  std::vector<int> roots_;
};

// Whether the checker of the screens (uv = 2 (x + 4, z + 4), 2 x 2 texels a repeat) is opaque at
// (x, z).
inline bool checker_opaque(float x, float z) {
  const int ix = int(std::floor(4.0f * (x + 4.0f))), iz = int(std::floor(4.0f * (z + 4.0f)));
  return ((ix + iz) & 1) == 0;
}

// The normal that the shared kernels bend to for a 8-bit texel (r, g, b), in the tangent frame.
inline vec3 decoded_normal(uint8_t r, uint8_t g, uint8_t b) {
  vec3 n(r / 255.0f * 2 - 1, g / 255.0f * 2 - 1, b / 255.0f * 2 - 1);
  return glm::normalize(n);
}

// Every feature scene in `dir`, with what it should render to.
inline std::vector<FeatureScene> feature_scenes(const fs::path& dir) {
  FeatureSceneBuilder f(dir);
  std::vector<FeatureScene> out;
  const vec3 down(0, -1, 0);
  const json floor = FeatureSceneBuilder::lambert(0.5f);
  const json black = FeatureSceneBuilder::lambert(0.0f);
  {
    GltfBuilder b = f.base(1, down, floor);
    out.push_back({"sun", f.write(b, "sun"), vec3(0.5f), "", "unshadowed floor: albedo x E / pi"});
  }
  {
    GltfBuilder b = f.base(1, down, floor);
    FeatureSceneBuilder::add_checker_texture(b);
    json mask = black;
    mask["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    mask["alphaMode"] = "MASK";
    f.add_screen(b, 2, true, mask);
    out.push_back({"mask_shadow", f.write(b, "mask_shadow"), vec3(0.25f), "", "MASK checker screen passes half the sun"});
  }
  {
    // For the light paths (no image): the checker screen white, so that paths stop on it and
    // deposit a VPL where it is opaque.
    GltfBuilder b = f.base(1, down, floor);
    FeatureSceneBuilder::add_checker_texture(b);
    json mask = FeatureSceneBuilder::lambert(0.8f);
    mask["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    mask["alphaMode"] = "MASK";
    f.add_screen(b, 2, false, mask);
    out.push_back({"mask_white", f.write(b, "mask_white"), vec3(0.0f), "", "light paths through the checker", true});
  }
  for (float alpha : {0.4f, 0.6f}) {
    GltfBuilder b = f.base(1, down, floor);
    json blend = black;
    blend["pbrMetallicRoughness"]["baseColorFactor"] = {0, 0, 0, alpha};
    blend["alphaMode"] = "BLEND";
    f.add_screen(b, 2, true, blend);
    const std::string name = alpha < 0.5f ? "blend_0.4" : "blend_0.6";
    out.push_back({name, f.write(b, name), vec3(alpha < 0.5f ? 0.5f : 0.0f), "",
                   alpha < 0.5f ? "BLEND alpha 0.4 (cutout at 0.5) passes all" : "BLEND alpha 0.6 passes none"});
  }
  {
    // Camera rays: an emissive floor seen through the checker from above.
    json glow = black;
    glow["emissiveFactor"] = {1, 1, 1};
    GltfBuilder b = f.base(3, vec3(0.0f), glow);
    FeatureSceneBuilder::add_checker_texture(b);
    json mask = black;
    mask["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    mask["alphaMode"] = "MASK";
    f.add_screen(b, 2, false, mask);
    out.push_back({"mask_camera", f.write(b, "mask_camera"), vec3(0.5f), "", "emissive floor seen through the checker"});
  }
  for (bool masked : {false, true}) {
    // An emitter: the checker screen emits downward; the masked one gives half the light.
    GltfBuilder b = f.base(1, vec3(0.0f), floor);
    FeatureSceneBuilder::add_checker_texture(b);
    json lamp = black;
    lamp["emissiveFactor"] = {1, 1, 1};
    if (masked) {
      lamp["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
      lamp["alphaMode"] = "MASK";
    }
    f.add_screen(b, 2, true, lamp);
    const std::string name = masked ? "mask_emitter" : "emitter";
    out.push_back({name, f.write(b, name), masked ? vec3(0.5f) : vec3(0.0f), masked ? "emitter" : "",
                   masked ? "MASK checker emitter: half of the unmasked one's light" : "unmasked emitter (reference)",
                   !masked});
  }
  {
    // COLOR_0: red from 0 (x = -4) to 1 (x = 4), green 0.25, blue 1; the view is symmetric in x.
    GltfBuilder b = f.base(1, down, floor, [](GltfBuilder& g) {
      return json{{"COLOR_0", g.vec3s({0, 0.25f, 1, 0, 0.25f, 1, 1, 0.25f, 1, 1, 0.25f, 1})}};
    });
    out.push_back({"color_0", f.write(b, "color_0"), vec3(0.25f, 0.125f, 0.5f), "", "COLOR_0 gradient x base colour"});
  }
  // Normal maps: a texel that bends the normal 45 degrees toward the tangent (or bitangent), the
  // sun 45 degrees from the zenith on that side (or the other): radiance 0.5 x cos.
  const float s = std::sqrt(0.5f);
  struct NormalCase {
    const char* name;
    uint8_t r, g, b;
    vec3 light;
    bool file_tangent;  // TANGENT (-1, 0, 0, 1) on every vertex
    bool mirrored;
    vec3 bent;  // the bent normal in world space
    const char* what;
  };
  const vec3 nt = decoded_normal(218, 128, 218), nb = decoded_normal(128, 218, 218);
  // Derived frames: tangent dp/du, bitangent -dp/dv = -z; normal +y.
  const NormalCase cases[] = {
      {"normal_u", 218, 128, 218, vec3(-s, -s, 0), false, false, vec3(nt.x, nt.z, -nt.y),
       "bent toward +u (derived tangent +x), sun on that side: cos 1"},
      {"normal_u_mirrored_uv", 218, 128, 218, vec3(-s, -s, 0), false, true, vec3(-nt.x, nt.z, -nt.y),
       "u mirrored: derived tangent -x, bent away from the sun: cos 0"},
      {"normal_v", 128, 218, 218, vec3(0, -s, s), false, false, vec3(nb.x, nb.z, -nb.y),
       "bent toward the bitangent -dp/dv = -z, sun on that side: cos 1"},
      {"normal_tangent_file", 218, 128, 218, vec3(-s, -s, 0), true, false, vec3(-nt.x, nt.z, nt.y),
       "TANGENT (-1, 0, 0, 1) overrides the uvs: bent toward -x, cos 0"},
  };
  {
    json mapped = floor;
    mapped["normalTexture"] = {{"index", 0}};
    GltfBuilder b = f.base(1, vec3(-s, -s, 0), mapped, {}, false, true);
    f.add_normal_texture(b, 218, 128, 218);
    out.push_back({"draco_normal_u", f.write(b, "draco_normal_u"), vec3(0.5f * (nt.x + nt.z) * s), "",
                   "normal_u with a Draco-compressed floor: positions, normals and uvs decoded"});
  }
  for (const NormalCase& c : cases) {
    json mapped = floor;
    mapped["normalTexture"] = {{"index", 0}};
    FeatureSceneBuilder::Attributes tangents;
    if (c.file_tangent)
      tangents = [](GltfBuilder& g) {
        std::vector<float> t;
        for (int i = 0; i < 4; ++i) t.insert(t.end(), {-1, 0, 0, 1});
        return json{{"TANGENT", g.accessor(g.view(t), kFloat, 4, "VEC4")}};
      };
    GltfBuilder b = f.base(1, c.light, mapped, tangents, c.mirrored);
    f.add_normal_texture(b, c.r, c.g, c.b);
    const float cosine = std::max(0.0f, glm::dot(c.bent, -glm::normalize(c.light)));
    out.push_back({c.name, f.write(b, c.name), vec3(0.5f * cosine), "", c.what});
  }
  return out;
}

}  // namespace sst::test
