// The glTF loader: a file's bytes checked (gltf_checks.h) and parsed by tinygltf, then converted
// into a Scene. The conversion walks the node instances (gltf_nodes.h) and places what hangs from
// them: mesh primitives as world-space triangles, perspective cameras and KHR_lights_punctual
// lights; it reads numbers through gltf_accessors.h, builds materials and textures with
// gltf_materials.h and gltf_textures.h, and the animation rig with gltf_animation.h.
#include "core/scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>

#include "core/scene/animation.h"
#include "core/scene/draco_mesh.h"
#include "core/scene/gltf_accessors.h"
#include "core/scene/gltf_animation.h"
#include "core/scene/gltf_checks.h"
#include "core/scene/gltf_context.h"
#include "core/scene/gltf_extensions.h"
#include "core/scene/gltf_materials.h"
#include "core/scene/gltf_nodes.h"
#include "core/scene/gltf_textures.h"
#include "core/scene/node_transform.h"
#include "core/util/error.h"

namespace sst::gltf {
namespace {

// The messages tinygltf gives for buffer files, reworded to say what is wrong with which file.
std::string tinygltf_error(const std::string& err) {
  std::string line = first_line(err);
  if (line.rfind("File not found : ", 0) == 0) return "buffer file not found: " + line.substr(17);
  if (line.rfind("File read error : ", 0) == 0) {
    std::string rest = line.substr(18);  // "<path> : <reason>"
    size_t colon = rest.rfind(" : ");
    return "cannot read buffer file " + (colon == std::string::npos ? rest : rest.substr(0, colon) + ": " + rest.substr(colon + 3));
  }
  // tinygltf appends the whole URI, which for a data URI is the whole buffer on one line.
  if (line.rfind("Failed to decode 'uri'", 0) == 0) return "a buffer's data URI is not base64 of byteLength bytes";
  if (line.rfind("File size mismatch : ", 0) == 0) {
    std::string rest = line.substr(21);  // "<path>, requestedBytes N, but got M"
    size_t comma = rest.rfind(", requestedBytes ");
    size_t got = rest.rfind(", but got ");
    if (comma != std::string::npos && got != std::string::npos && got > comma)
      return "buffer file " + rest.substr(0, comma) + " has " + rest.substr(got + 10) + " bytes, the glTF says " +
             rest.substr(comma + 17, got - comma - 17);
  }
  if (line.find("parse_error") != std::string::npos || line.find("JSON string too short") != std::string::npos) {
    size_t bracket = line.find("] ");
    if (line.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) line = line.substr(bracket + 2);
    return "malformed JSON: " + line;
  }
  return line;
}

// tinygltf's file callbacks, except that only regular files are read: its own FileExists opens
// the file, which blocks forever on a FIFO, and a directory reads as 2^63 bytes.
bool path_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}
bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    if (err) *err = "not a regular file";
    return false;
  }
  return tinygltf::ReadWholeFile(out, err, path, user);
}

// The bytes checked (gltf_checks.h) and parsed by tinygltf, its images kept encoded
// (gltf_textures.h) and its buffers read only from regular files.
tinygltf::Model parse(std::string_view bytes, const std::string& base_dir, const std::string& name) {
  if (bytes.size() > size_t(UINT32_MAX)) throw Error(name + ": file larger than 4 GiB");
  bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  const std::string_view json_text = binary ? checked_glb_json(bytes, name) : bytes;
  check_gltf_json(json_text, name);
  std::string rewritten;
  if (std::optional<std::string> j = without_draco_index_accessors(json_text)) {
    rewritten = binary ? glb_with_json(bytes, json_text, std::move(*j)) : std::move(*j);
    bytes = rewritten;
  }
  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(&keep_encoded_image, nullptr);
  gltf.SetFsCallbacks({&path_exists, &tinygltf::ExpandFilePath, &read_regular_file, &tinygltf::WriteWholeFile, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  bool ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                               unsigned(bytes.size()), base_dir)
                   : gltf.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
  if (!ok) throw Error(name + ": " + tinygltf_error(err.empty() ? warn : err));
  return model;
}

// One model's conversion into a Scene. The steps run in a fixed order, which is also the order of
// the Scene's warnings: extensions, nodes and animations, then each instance's mesh, camera and
// light, then materials, textures and the animation rig.
class Converter {
 public:
  Converter(const tinygltf::Model& model, const std::string& file, Scene& scene)
      : ctx_(model, file), model_(model), accessors_(ctx_), materials_(ctx_), scene_(scene) {}

  void run() {
    check_extensions(ctx_);
    note_ignored_features();
    accessors_.check_implicit();
    std::vector<Instance> instances = traverse_nodes(ctx_);
    std::vector<int> rig_node = build_rig_nodes(ctx_, instances, read_animations(ctx_, accessors_), rig_);
    for (size_t i = 0; i < instances.size(); ++i) {
      const Instance& inst = instances[i];
      const tinygltf::Node& node = model_.nodes[inst.node];
      int moving = rig_node[i];
      if (node.mesh >= 0) add_mesh(inst, moving);
      if (node.camera >= 0) {
        size_t before = scene_.cameras.size();
        add_camera(inst);
        if (moving >= 0 && scene_.cameras.size() > before) rig_.cameras.push_back({moving, uint32_t(before)});
      }
      if (const tinygltf::Value* ext = extension(node.extensions, "KHR_lights_punctual")) {
        size_t before = scene_.lights.size();
        add_light(inst, *ext);
        if (moving >= 0 && scene_.lights.size() > before) rig_.lights.push_back({moving, uint32_t(before)});
      }
    }
    if (scene_.triangles.empty()) fail("scene has no triangles");
    if (degenerate_triangles_ > 0)
      ctx_.warnings.add("dropped " + std::to_string(degenerate_triangles_) + " zero-area triangles");
    materials_.build(scene_);
    scene_.textures = decode_textures(ctx_, accessors_, materials_.texture_keys());
    scene_.finalize_bounds();
    attach_animation(std::move(rig_), scene_);
    if (scene_.cameras.empty()) add_auto_camera();
    if (!scene_has_lights()) ctx_.warnings.add("scene has no lights: the image will be black");
    ctx_.warnings.append_to(scene_.warnings);
    if (ctx_.quantization) ctx_.uses.insert("KHR_mesh_quantization");
    if (!scene_.colors.empty()) scene_.colors.resize(scene_.positions.size(), vec4(1.0f));
    if (!scene_.tangents.empty()) scene_.tangents.resize(scene_.positions.size(), vec4(0.0f));
    scene_.gltf_features.assign(ctx_.uses.begin(), ctx_.uses.end());
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { ctx_.fail(problem); }

  void note_ignored_features() {
    if (!model_.skins.empty()) ctx_.warnings.add("skins ignored: the rest pose is rendered");
  }

  // ---- geometry ----

  struct Attributes {
    const std::vector<float>* positions = nullptr;
    const std::vector<float>* normals = nullptr;
    const std::vector<float>* uvs = nullptr;
    const std::vector<float>* colors = nullptr;    // COLOR_0, color_components (3 or 4) per vertex
    int color_components = 4;
    const std::vector<float>* tangents = nullptr;  // TANGENT, 4 per vertex
    size_t count = 0;
  };

  // `draco`: the primitive's decoded KHR_draco_mesh_compression data, whose attributes replace
  // the accessors' (and skip their type rules: the decoder returns floats).
  Attributes read_attributes(const tinygltf::Primitive& prim, const std::string& what, int uv_set,
                             const DracoPrimitive* draco) {
    using namespace std::string_literals;
    constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE,
                  UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, S = TINYGLTF_COMPONENT_TYPE_SHORT,
                  US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    auto require = [&](int index, std::initializer_list<int> allowed, bool normalized_only, const char* semantic) {
      if (!(draco && draco->attributes.count(semantic))) accessors_.require_types(index, allowed, normalized_only, what + " " + semantic);
    };
    auto values = [&](int index, int components, const char* semantic) -> const std::vector<float>* {
      if (draco && draco->attributes.count(semantic)) {
        if (draco->components.at(semantic) != components)
          fail(what + " Draco attribute " + semantic + " has " + std::to_string(draco->components.at(semantic)) +
               " components (needs " + std::to_string(components) + ")");
        return &draco->attributes.at(semantic);
      }
      return &accessors_.float_attribute(index, components, semantic, what);
    };
    Attributes at;
    int pos = prim.attributes.at("POSITION");
    if (ctx_.quantization) require(pos, {F, B, UB, S, US}, false, "POSITION");
    else require(pos, {F}, false, "POSITION");
    at.positions = values(pos, 3, "POSITION");
    at.count = at.positions->size() / 3;
    auto same_count = [&](const std::vector<float>& v, size_t comps, const char* semantic) {
      if (v.size() / comps != at.count)
        fail(what + " " + semantic + " has " + std::to_string(v.size() / comps) + " elements but POSITION has " +
             std::to_string(at.count));
    };
    if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
      if (ctx_.quantization) require(it->second, {F, B, S}, true, "NORMAL");
      else require(it->second, {F}, false, "NORMAL");
      at.normals = values(it->second, 3, "NORMAL");
      same_count(*at.normals, 3, "NORMAL");
    }
    const std::string texcoord = "TEXCOORD_" + std::to_string(uv_set);
    if (auto it = prim.attributes.find(texcoord); it != prim.attributes.end()) {
      if (ctx_.quantization) require(it->second, {F, B, UB, S, US}, false, texcoord.c_str());
      else require(it->second, {F, UB, US}, true, texcoord.c_str());
      at.uvs = values(it->second, 2, texcoord.c_str());
      same_count(*at.uvs, 2, texcoord.c_str());
    } else if (uv_set > 0) {
      fail(what + " has no " + texcoord + ", which its material's textures use");
    }
    if (auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
      require(it->second, {F, UB, US}, true, "COLOR_0");
      if (draco && draco->components.count("COLOR_0")) {
        at.color_components = draco->components.at("COLOR_0") == 3 ? 3 : 4;
      } else {
        const tinygltf::Accessor& a = accessors_.accessor(it->second, what + " COLOR_0");
        at.color_components = a.type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
      }
      at.colors = values(it->second, at.color_components, "COLOR_0");
      same_count(*at.colors, size_t(at.color_components), "COLOR_0");
      ctx_.uses.insert("COLOR_0");
    }
    if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
      if (ctx_.quantization) require(it->second, {F, B, S}, true, "TANGENT");
      else require(it->second, {F}, false, "TANGENT");
      at.tangents = values(it->second, 4, "TANGENT");
      same_count(*at.tangents, 4, "TANGENT");
      ctx_.uses.insert("TANGENT");
    }
    return at;
  }

  std::vector<uint32_t> read_indices(const tinygltf::Primitive& prim, size_t vertex_count, const std::string& what) const {
    std::vector<uint32_t> idx;
    if (prim.indices < 0) {
      idx.resize(vertex_count);
      std::iota(idx.begin(), idx.end(), 0u);
      return idx;
    }
    accessors_.require_types(prim.indices,
                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                  false, what + " indices");
    idx = accessors_.read<uint32_t>(prim.indices, 1, what + " indices");
    for (uint32_t i : idx)
      if (i >= vertex_count)
        fail(what + " has vertex index " + std::to_string(i) + " out of range (vertex count " + std::to_string(vertex_count) + ")");
    return idx;
  }

  // TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN as a triangle list, in glTF's winding order.
  std::vector<uvec3> assemble(int mode, const std::vector<uint32_t>& idx, const std::string& what) {
    std::vector<uvec3> tris;
    size_t n = idx.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (n % 3 != 0) ctx_.warnings.add("index count not a multiple of 3: trailing indices ignored");
      for (size_t i = 0; i + 2 < n; i += 3) tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < n; ++i)
        tris.push_back(i % 2 == 0 ? uvec3(idx[i], idx[i + 1], idx[i + 2]) : uvec3(idx[i + 1], idx[i], idx[i + 2]));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t i = 1; i + 1 < n; ++i) tris.emplace_back(idx[i], idx[i + 1], idx[0]);
    }
    return tris;
  }

  // A mesh under a moving node (rig_node >= 0) also keeps its vertices in object space.
  void add_mesh(const Instance& inst, int rig_node) {
    int mesh_index = model_.nodes[inst.node].mesh;
    if (size_t(mesh_index) >= model_.meshes.size())
      fail(quoted_name("node", inst.node, model_.nodes[inst.node].name) + " refers to missing mesh " + std::to_string(mesh_index));
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    AnimatedMesh moving;
    moving.node = rig_node;
    moving.first_vertex = uint32_t(scene_.positions.size());
    moving.first_triangle = uint32_t(scene_.triangles.size());
    recording_ = rig_node >= 0 ? &moving : nullptr;
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      add_primitive(mesh.primitives[p], inst.world, quoted_name("mesh", mesh_index, mesh.name) + " primitive " + std::to_string(p));
    recording_ = nullptr;
    moving.triangle_count = uint32_t(scene_.triangles.size() - moving.first_triangle);
    if (rig_node >= 0 && !moving.positions.empty()) rig_.meshes.push_back(std::move(moving));
  }


  static const char* mode_name(int mode) {
    switch (mode) {
      case TINYGLTF_MODE_POINTS: return "POINTS";
      case TINYGLTF_MODE_LINE: return "LINES";
      case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
      case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
      default: return nullptr;
    }
  }

  void add_primitive(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& what) {
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      const char* name = mode_name(mode);
      ctx_.warnings.add(name ? std::string(name) + " primitives skipped (only triangles are rendered)"
                         : "primitives of unknown mode " + std::to_string(mode) + " skipped");
      return;
    }
    if (!prim.attributes.count("POSITION")) {
      ctx_.warnings.add("primitives without POSITION skipped");
      return;
    }
    if (!prim.targets.empty()) ctx_.warnings.add("morph targets ignored: the base shape is rendered");
    int gltf_material = prim.material;
    if (gltf_material >= int(model_.materials.size())) fail(what + " refers to missing material " + std::to_string(gltf_material));
    uint32_t material = gltf_material < 0 ? uint32_t(model_.materials.size()) : uint32_t(gltf_material);

    const UvMapping& uv = materials_.uv_mapping(gltf_material);
    const DracoPrimitive* draco = accessors_.draco_primitive(prim, what);
    Attributes at = read_attributes(prim, what, uv.set, draco);
    std::vector<float> mapped_uvs;
    if (at.uvs && !uv.affine_identity()) {
      mapped_uvs = uv.apply(*at.uvs);
      at.uvs = &mapped_uvs;
    }
    std::vector<uvec3> tris = assemble(mode, draco ? draco->indices : read_indices(prim, at.count, what), what);
    if (at.normals) append_smooth(at, tris, world, material, what);
    else append_flat(at, tris, world, material, what);
  }

  static vec3 object_position(const Attributes& at, uint32_t i) {
    const std::vector<float>& p = *at.positions;
    return vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  }

  vec3 world_position(const WorldTransform& t, const Attributes& at, uint32_t i, const std::string& what) const {
    vec3 out = transform_point(t, object_position(at, i));
    if (!is_finite(out)) fail(what + " has a vertex that is not finite in world space (vertex " + std::to_string(i) + ")");
    return out;
  }

  vec2 uv_of(const Attributes& at, uint32_t i) const {
    return at.uvs ? vec2((*at.uvs)[2 * i], (*at.uvs)[2 * i + 1]) : vec2(0.0f);
  }

  // COLOR_0 and TANGENT of the vertex just appended from object vertex i: the scene's arrays stay
  // empty until a primitive has them, then hold every vertex (defaults where a primitive has
  // none). Tangents of moving meshes are left zero, so that the kernels derive them from the
  // posed triangle.
  void append_vertex_extras(const Attributes& at, uint32_t i, const WorldTransform& t) {
    const size_t before = scene_.positions.size() - 1;
    if (at.colors || !scene_.colors.empty()) {
      scene_.colors.resize(before, vec4(1.0f));
      vec4 c(1.0f);
      if (at.colors) {
        const float* v = at.colors->data() + size_t(at.color_components) * i;
        c = vec4(v[0], v[1], v[2], at.color_components == 4 ? v[3] : 1.0f);
      }
      scene_.colors.push_back(glm::clamp(c, vec4(0.0f), vec4(1.0f)));
    }
    if (at.tangents || !scene_.tangents.empty()) {
      scene_.tangents.resize(before, vec4(0.0f));
      vec4 out(0.0f);
      if (at.tangents && !recording_) {
        const float* v = at.tangents->data() + 4 * size_t(i);
        const vec3 world = vec3(glm::dmat3(t.m) * glm::dvec3(v[0], v[1], v[2]));
        // A mirroring transform reverses cross(normal, tangent): the bitangent keeps its side.
        const float w = (v[3] < 0.0f) != t.mirrored ? -1.0f : 1.0f;
        if (usable(world)) out = vec4(unit(world), w);
      }
      scene_.tangents.push_back(out);
    }
  }

  uint32_t checked_vertex_base(size_t extra, const std::string& what) const {
    if (scene_.positions.size() + extra >= size_t(UINT32_MAX)) fail("too many vertices (more than 2^32) at " + what);
    return uint32_t(scene_.positions.size());
  }

  // Primitives with normals keep their shared vertices; only the vertices the triangles use are
  // copied, because exporters often let many primitives index one large vertex accessor.
  void append_smooth(const Attributes& at, const std::vector<uvec3>& tris, const glm::dmat4& world, uint32_t material,
                     const std::string& what) {
    WorldTransform t = world_transform(world);
    std::unordered_map<uint32_t, uint32_t> remap;
    std::vector<char> needs_normal;  // per new vertex: its normal had zero length
    auto vertex = [&](uint32_t i) -> uint32_t {
      auto [it, fresh] = remap.try_emplace(i, 0);
      if (!fresh) return it->second;
      it->second = checked_vertex_base(1, what);
      scene_.positions.push_back(world_position(t, at, i, what));
      append_vertex_extras(at, i, t);
      const auto& n = *at.normals;
      vec3 object_normal(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
      if (recording_) {
        recording_->positions.push_back(object_position(at, i));
        recording_->normals.push_back(object_normal);
      }
      vec3 wn = transform_normal(t, object_normal);
      needs_normal.push_back(!usable(wn));
      scene_.normals.push_back(usable(wn) ? unit(wn) : vec3(0.0f));
      scene_.uvs.push_back(uv_of(at, i));
      return it->second;
    };
    uint32_t base = uint32_t(scene_.positions.size());
    size_t first_triangle = scene_.triangles.size();
    for (uvec3 tri : tris) {
      if (t.mirrored) std::swap(tri.y, tri.z);
      uvec3 v(vertex(tri.x), vertex(tri.y), vertex(tri.z));
      if (!usable(face_normal(scene_.positions[v.x], scene_.positions[v.y], scene_.positions[v.z]))) {
        ++degenerate_triangles_;
        continue;
      }
      scene_.triangles.push_back(v);
      scene_.triangle_material.push_back(material);
    }
    if (std::find(needs_normal.begin(), needs_normal.end(), 1) != needs_normal.end()) {
      set_geometric_normals(scene_.positions, std::span<const uvec3>(scene_.triangles).subspan(first_triangle), base,
                            needs_normal, scene_.normals);
      ctx_.warnings.add("zero-length vertex normals replaced by the geometric normal");
    }
  }

  // glTF: without NORMAL, a primitive is flat shaded; each triangle gets its own three vertices.
  void append_flat(const Attributes& at, const std::vector<uvec3>& tris, const glm::dmat4& world, uint32_t material,
                   const std::string& what) {
    ctx_.warnings.add("primitives without NORMAL: flat normals generated");
    WorldTransform t = world_transform(world);
    for (uvec3 tri : tris) {
      if (t.mirrored) std::swap(tri.y, tri.z);
      vec3 p[3];
      for (int k = 0; k < 3; ++k) p[k] = world_position(t, at, tri[k], what);
      vec3 fn = face_normal(p[0], p[1], p[2]);
      if (!usable(fn)) {
        ++degenerate_triangles_;
        continue;
      }
      uint32_t b = checked_vertex_base(3, what);
      for (int k = 0; k < 3; ++k) {
        scene_.positions.push_back(p[k]);
        append_vertex_extras(at, tri[k], t);
        scene_.normals.push_back(unit(fn));
        scene_.uvs.push_back(uv_of(at, tri[k]));
        if (recording_) {  // a zero normal: posing rebuilds it from the face, as here
          recording_->positions.push_back(object_position(at, tri[k]));
          recording_->normals.push_back(vec3(0.0f));
        }
      }
      scene_.triangles.emplace_back(b, b + 1, b + 2);
      scene_.triangle_material.push_back(material);
    }
  }

  // ---- cameras and lights ----

  void add_camera(const Instance& inst) {
    const tinygltf::Node& node = model_.nodes[inst.node];
    if (size_t(node.camera) >= model_.cameras.size())
      fail(quoted_name("node", inst.node, node.name) + " refers to missing camera " + std::to_string(node.camera));
    const tinygltf::Camera& cam = model_.cameras[node.camera];
    std::string name = !cam.name.empty() ? cam.name : !node.name.empty() ? node.name : "camera" + std::to_string(node.camera);
    if (cam.type != "perspective") {
      ctx_.warnings.add("camera '" + name + "' is " + (cam.type.empty() ? "untyped" : cam.type) + ": skipped (only perspective cameras)");
      return;
    }
    double yfov = cam.perspective.yfov, aspect = cam.perspective.aspectRatio;
    if (!(yfov > 0.0 && yfov < kPi)) fail("camera '" + name + "' has yfov " + std::to_string(yfov) + " (must be in (0, pi))");
    if (!(aspect >= 0.0 && std::isfinite(aspect))) fail("camera '" + name + "' has aspectRatio " + std::to_string(aspect));
    Camera c;
    if (!place_camera(inst.world, c)) {
      ctx_.warnings.add("camera '" + name + "' has a degenerate node transform: skipped");
      return;
    }
    c.name = name;
    c.yfov = float(yfov);
    c.aspect = float(aspect);
    scene_.cameras.push_back(c);
  }

  void add_light(const Instance& inst, const tinygltf::Value& ext) {
    const tinygltf::Node& node = model_.nodes[inst.node];
    const tinygltf::Value* index_value = member(ext, "light");
    int index = index_value && index_value->IsNumber() ? index_value->GetNumberAsInt() : -1;
    if (index < 0 || size_t(index) >= model_.lights.size())
      fail(quoted_name("node", inst.node, node.name) + " refers to missing light " + std::to_string(index));
    const tinygltf::Light& l = model_.lights[index];
    PunctualLight out;
    out.name = !l.name.empty() ? l.name : !node.name.empty() ? node.name : "light" + std::to_string(index);
    std::string what = "light '" + out.name + "'";
    if (l.type == "point") out.type = LightType::Point;
    else if (l.type == "spot") out.type = LightType::Spot;
    else if (l.type == "directional") out.type = LightType::Directional;
    else {
      ctx_.warnings.add(what + " has unknown type '" + l.type + "': skipped");
      return;
    }
    glm::dvec3 color(1.0);
    if (!l.color.empty()) {
      if (l.color.size() != 3) fail(what + " has a color of " + std::to_string(l.color.size()) + " numbers (needs 3)");
      color = glm::dvec3(l.color[0], l.color[1], l.color[2]);
    }
    out.intensity = vec3(color * l.intensity);
    if (!is_finite(out.intensity) || glm::any(glm::lessThan(out.intensity, vec3(0.0f))))
      fail(what + " has a negative or non-finite color * intensity");
    if (l.range > 0.0) ctx_.warnings.add("light range ignored: pure inverse-square falloff, as in the references");
    if (!place_light(inst.world, out)) fail(what + " has a degenerate node transform (no direction)");
    if (out.type == LightType::Spot) set_cone(l.spot, what, out);
    scene_.lights.push_back(out);
  }

  // glTF requires 0 <= inner < outer <= pi/2; values outside are clamped with a warning.
  void set_cone(const tinygltf::SpotLight& spot, const std::string& what, PunctualLight& out) {
    double outer = spot.outerConeAngle, inner = spot.innerConeAngle;
    if (!std::isfinite(outer) || !std::isfinite(inner)) fail(what + " has a non-finite cone angle");
    double clamped_outer = std::clamp(outer, 0.0, double(kPi) / 2.0);
    double clamped_inner = std::clamp(inner, 0.0, clamped_outer);
    if (clamped_outer != outer || clamped_inner != inner)
      ctx_.warnings.add(what + " cone angles outside 0 <= inner <= outer <= pi/2: clamped");
    out.cos_outer = float(std::cos(clamped_outer));
    out.cos_inner = float(std::cos(clamped_inner));
  }

  // Looks down -Z at the bounding box from +Z, far enough that its bounding sphere fits the
  // vertical field of view (and the horizontal one at any aspect >= 1).
  void add_auto_camera() {
    Camera c;
    c.name = "auto";
    c.yfov = 0.8f;
    float radius = std::max(0.5f * scene_.bounds.diagonal(), 1e-6f);
    float distance = radius / std::sin(0.5f * c.yfov);
    c.eye = scene_.bounds.center() + vec3(0.0f, 0.0f, distance);
    scene_.cameras.push_back(c);
    ctx_.warnings.add("scene has no perspective camera: added camera 'auto' framing the bounding box from +Z");
  }

  bool scene_has_lights() const {
    if (!scene_.lights.empty()) return true;
    for (uint32_t m : scene_.triangle_material)
      if (scene_.material_emits(m)) return true;
    return false;
  }

  Context ctx_;
  const tinygltf::Model& model_;
  Accessors accessors_;
  Materials materials_;
  Scene& scene_;
  AnimationRig rig_;
  AnimatedMesh* recording_ = nullptr;  // the moving mesh whose object-space vertices are kept
  size_t degenerate_triangles_ = 0;
};

}  // namespace
}  // namespace sst::gltf

namespace sst {

Scene load_gltf_from_memory(std::string_view bytes, const std::string& base_dir, const std::string& name) {
  tinygltf::Model model = gltf::parse(bytes, base_dir, name);
  Scene scene;
  scene.source = name;
  gltf::Converter(model, name, scene).run();
  return scene;
}

Scene load_gltf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path + ": file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": not a regular file");  // a FIFO would block
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw Error(path + ": cannot read file");
  std::string base_dir = std::filesystem::path(path).parent_path().string();
  return load_gltf_from_memory(bytes, base_dir, path);
}

}  // namespace sst
