#include "core/scene/gltf_loader.h"

#include "core/image/image.h"

#include <stb/stb_image.h>
#include <tbb/parallel_for.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "core/scene/animation.h"
#include "core/scene/draco_mesh.h"
#include "core/scene/encoded_image.h"
#include "core/scene/node_transform.h"
#include "core/util/error.h"
#include "core/util/json_io.h"
#include "core/util/machine_info.h"

namespace sst {
namespace {

// ---------------------------------------------------------------------------------------------
// Extensions
// ---------------------------------------------------------------------------------------------

// Required extensions we accept. glTF obliges a loader to refuse a file that requires anything
// else, so the table holds only what we implement or what cannot change the image.
struct AcceptedExtension {
  std::string_view name;
  std::string_view why;
};
constexpr std::array kAcceptedRequiredExtensions = {
    AcceptedExtension{"KHR_draco_mesh_compression", "implemented: decoded with Draco (core/scene/draco_mesh.h)"},
    AcceptedExtension{"KHR_lights_punctual", "implemented: point, spot and directional lights"},
    AcceptedExtension{"KHR_materials_emissive_strength", "implemented: scales emissiveFactor"},
    AcceptedExtension{"KHR_mesh_quantization", "implemented: integer POSITION/NORMAL/TEXCOORD_n"},
    AcceptedExtension{"KHR_texture_transform", "implemented: applied to the UVs (one per material)"},
    AcceptedExtension{"KHR_xmp_json_ld", "metadata only"},
};
// Extensions that are used, not required, and that we implement: no "ignored" warning.
constexpr std::array<std::string_view, 5> kImplementedExtensions = {
    "KHR_draco_mesh_compression", "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_mesh_quantization",
    "KHR_texture_transform"};

template <class Table>
bool contains(const Table& table, std::string_view name) {
  for (const auto& entry : table) {
    if constexpr (std::is_same_v<std::decay_t<decltype(entry)>, AcceptedExtension>) {
      if (entry.name == name) return true;
    } else if (entry == name) {
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------------------------
// Small helpers
// ---------------------------------------------------------------------------------------------

// Each distinct message once, in order of first appearance, with a count when it repeats.
class Warnings {
 public:
  void add(const std::string& message) {
    auto [it, fresh] = count_.try_emplace(message, 0);
    if (fresh) order_.push_back(message);
    ++it->second;
  }
  void append_to(std::vector<std::string>& out) const {
    for (const std::string& m : order_) {
      size_t n = count_.at(m);
      out.push_back(n > 1 ? m + " (" + std::to_string(n) + " times)" : m);
    }
  }

 private:
  std::vector<std::string> order_;
  std::unordered_map<std::string, size_t> count_;
};

// tinygltf reports errors as several lines, sometimes with a nlohmann exception prefix; we
// want one line.
std::string first_line(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    size_t e = line.find_last_not_of(" \t\r");
    return line.substr(b, e - b + 1);
  }
  return "unknown error";
}

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

const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key) {
  if (!object.IsObject() || !object.Has(key)) return nullptr;
  return &object.Get(key);
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const std::string& name) {
  auto it = extensions.find(name);
  return it == extensions.end() ? nullptr : &it->second;
}

double number_or(const tinygltf::Value* v, double fallback) {
  return v && v->IsNumber() ? v->GetNumberAsDouble() : fallback;
}

std::string quoted_name(const std::string& kind, size_t index, const std::string& name) {
  return kind + " " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
}

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

// Decoding is deferred (see decode_images) so that images decode in parallel and only when a
// material uses them. Images in bufferViews are re-read later with bounds checks, because
// tinygltf hands this callback a pointer it has not checked.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

Wrap wrap_mode(int gl_wrap, Warnings& warnings) {
  switch (gl_wrap) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
    default:
      warnings.add("unknown sampler wrap mode " + std::to_string(gl_wrap) + ": REPEAT used");
      return Wrap::Repeat;
  }
}

bool valid_decoded(const tinygltf::Image& img) {
  if (img.width < 1 || img.height < 1 || img.component < 1 || img.component > 4) return false;
  if (img.bits != 8 && img.bits != 16) return false;
  return img.image.size() >= size_t(img.width) * size_t(img.height) * size_t(img.component) * size_t(img.bits / 8);
}

// An 8- or 16-bit image with 1-4 channels -> RGBA (grey expands to RGB, missing alpha is 1).
// 8-bit images stay 8-bit, sRGB-encoded if colour (decoded per fetch); 16-bit ones become
// linear floats. Colour textures are sRGB; alpha never is.
Texture to_texture(const tinygltf::Image& img, bool srgb) {
  Texture t;
  t.width = img.width;
  t.height = img.height;
  size_t texels = size_t(img.width) * size_t(img.height);
  int channels = img.component;
  auto expand = [channels](auto channel, auto one) {
    using T = decltype(one);
    std::array<T, 4> v{T(0), T(0), T(0), one};
    if (channels <= 2) {
      v[0] = v[1] = v[2] = channel(0);
      if (channels == 2) v[3] = channel(1);
    } else {
      for (int c = 0; c < 3; ++c) v[c] = channel(c);
      if (channels == 4) v[3] = channel(3);
    }
    return v;
  };
  if (img.bits == 8) {
    t.srgb = srgb;
    t.rgba8.resize(texels);
    for (size_t i = 0; i < texels; ++i) {
      const unsigned char* p = img.image.data() + i * channels;
      auto v = expand([p](int c) { return uint32_t(p[c]); }, uint32_t(255));
      t.rgba8[i] = v[0] | (v[1] << 8) | (v[2] << 16) | (v[3] << 24);
    }
    return t;
  }
  t.texels.resize(texels);
  for (size_t i = 0; i < texels; ++i) {
    const unsigned char* p = img.image.data() + i * channels * 2;
    auto v = expand(
        [p, srgb](int c) {
          uint16_t raw;
          std::memcpy(&raw, p + 2 * c, 2);
          float f = float(raw) / 65535.0f;
          return srgb && c < 3 ? srgb_decode(f) : f;
        },
        1.0f);
    t.texels[i] = vec4(v[0], v[1], v[2], v[3]);
  }
  return t;
}

// ---------------------------------------------------------------------------------------------
// The conversion
// ---------------------------------------------------------------------------------------------

struct Instance {
  int node;
  int parent;  // index of the parent's Instance, -1 for a root
  glm::dmat4 world;
};

// The UVs a material's textures are sampled at: TEXCOORD_<set>, mapped by the affine transform
// u' = u[0] u + u[1] v + u[2], v' = v[0] u + v[1] v + v[2] (KHR_texture_transform).
constexpr int kMaxUvSet = 7;
struct UvMapping {
  int set = 0;
  std::array<double, 3> u{1.0, 0.0, 0.0};
  std::array<double, 3> v{0.0, 1.0, 0.0};
  bool operator==(const UvMapping&) const = default;
  bool affine_identity() const { return u == UvMapping{}.u && v == UvMapping{}.v; }
  std::vector<float> apply(const std::vector<float>& uvs) const {
    std::vector<float> out(uvs.size());
    for (size_t i = 0; i + 1 < uvs.size(); i += 2) {
      out[i] = float(u[0] * uvs[i] + u[1] * uvs[i + 1] + u[2]);
      out[i + 1] = float(v[0] * uvs[i] + v[1] * uvs[i + 1] + v[2]);
    }
    return out;
  }
};

// One texture per (image, colour space, sampler) actually used.
struct TextureKey {
  int image;
  bool srgb;
  int sampler;
  auto operator<=>(const TextureKey&) const = default;
};

class GltfConverter {
 public:
  GltfConverter(const tinygltf::Model& model, const std::string& file, Scene& scene)
      : model_(model), file_(file), scene_(scene) {}

  void run() {
    check_extensions();
    note_ignored_features();
    check_implicit_accessors();
    std::vector<Instance> instances = traverse_nodes();
    std::vector<int> rig_node = build_rig_nodes(instances, read_animations());
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
      warnings_.add("dropped " + std::to_string(degenerate_triangles_) + " zero-area triangles");
    build_materials();
    decode_textures();
    scene_.finalize_bounds();
    attach_animation();
    if (scene_.cameras.empty()) add_auto_camera();
    if (!scene_has_lights()) warnings_.add("scene has no lights: the image will be black");
    warnings_.append_to(scene_.warnings);
    if (quantization_) uses_.insert("KHR_mesh_quantization");
    if (!scene_.colors.empty()) scene_.colors.resize(scene_.positions.size(), vec4(1.0f));
    if (!scene_.tangents.empty()) scene_.tangents.resize(scene_.positions.size(), vec4(0.0f));
    scene_.gltf_features.assign(uses_.begin(), uses_.end());
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw Error(file_ + ": " + problem); }

  // ---- extensions and features we do not model ----

  void check_extensions() {
    for (const std::string& name : model_.extensionsRequired) {
      if (!contains(kAcceptedRequiredExtensions, name))
        fail("requires unsupported extension " + name);
    }
    for (const std::string& name : model_.extensionsUsed) {
      if (name == "KHR_mesh_quantization") quantization_ = true;
      if (!contains(kImplementedExtensions, name))
        warnings_.add("extension " + name + " is not supported: ignored");
    }
    if (contains(model_.extensionsRequired, std::string_view("KHR_mesh_quantization"))) quantization_ = true;
  }

  void note_ignored_features() {
    if (!model_.skins.empty()) warnings_.add("skins ignored: the rest pose is rendered");
  }

  // ---- node hierarchy ----

  // A node's rest transform, checked: a matrix, or translation, rotation and scale.
  RigNode rest_node(int index) const {
    const tinygltf::Node& n = model_.nodes[index];
    std::string what = quoted_name("node", index, n.name);
    RigNode out;
    out.name = n.name;
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) fail(what + " has a matrix of " + std::to_string(n.matrix.size()) + " numbers (needs 16)");
      if (!all_finite(n.matrix)) fail(what + " has a non-finite matrix");
      glm::dmat4 M(1.0);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) M[c][r] = n.matrix[c * 4 + r];  // column-major, as glTF
      out.matrix = M;
      return out;
    }
    auto check = [&](const std::vector<double>& v, size_t size, const char* field) {
      if (!v.empty() && v.size() != size) fail(what + " has a " + field + " of " + std::to_string(v.size()) + " numbers");
      if (!all_finite(v)) fail(what + " has a non-finite " + field);
    };
    check(n.translation, 3, "translation");
    check(n.rotation, 4, "rotation");
    check(n.scale, 3, "scale");
    if (!n.translation.empty()) out.translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
    if (!n.rotation.empty()) out.rotation = glm::dvec4(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]);
    if (!n.scale.empty()) out.scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
    if (!(glm::dot(out.rotation, out.rotation) > 0.0)) fail(what + " has a zero rotation quaternion");
    return out;
  }

  std::vector<int> root_nodes() const {
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene;
      if (s >= int(model_.scenes.size())) fail("default scene " + std::to_string(s) + " does not exist");
      if (s < 0) s = 0;
      return model_.scenes[s].nodes;
    }
    std::vector<char> is_child(model_.nodes.size(), 0);
    for (const tinygltf::Node& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < model_.nodes.size()) is_child[c] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(int(i));
    return roots;
  }

  // Iterative, so that a deep hierarchy cannot overflow the stack; a path longer than the node
  // count means a cycle. Each node may have one parent (glTF), which bounds the instance count.
  std::vector<Instance> traverse_nodes() const {
    size_t count = model_.nodes.size();
    std::vector<int> parents(count, 0);
    for (size_t i = 0; i < count; ++i)
      for (int c : model_.nodes[i].children) {
        if (c < 0 || size_t(c) >= count) fail(quoted_name("node", i, model_.nodes[i].name) + " has missing child " + std::to_string(c));
        if (++parents[c] > 1) fail(quoted_name("node", c, model_.nodes[c].name) + " has more than one parent");
      }
    std::vector<Instance> out;
    struct Item { int node; int parent; size_t depth; };
    std::vector<Item> stack;
    std::vector<int> roots = root_nodes();
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
      if (*it < 0 || size_t(*it) >= count) fail("scene lists missing node " + std::to_string(*it));
      stack.push_back({*it, -1, 0});
    }
    while (!stack.empty()) {
      Item item = stack.back();
      stack.pop_back();
      if (item.depth > count) fail("node hierarchy has a cycle through node " + std::to_string(item.node));
      glm::dmat4 parent_world = item.parent >= 0 ? out[item.parent].world : glm::dmat4(1.0);
      out.push_back({item.node, item.parent, parent_world * rest_node(item.node).local_matrix()});
      int self = int(out.size()) - 1;
      const auto& children = model_.nodes[item.node].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, self, item.depth + 1});
    }
    return out;
  }

  // ---- animations ----

  // Every animation plays at once on one clock. A target animated by two animations follows the
  // later one (glTF forbids two channels on one target only within an animation). Channels on
  // morph target weights are ignored, as morph targets are. AnimationChannel::node is the glTF
  // node here; build_rig_nodes maps it to the rig.
  std::vector<AnimationChannel> read_animations() {
    std::vector<AnimationChannel> out;
    std::map<std::pair<int, AnimatedProperty>, size_t> animated_by;  // target -> animation
    size_t weight_channels = 0;
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& animation = model_.animations[a];
      std::string animation_name = quoted_name("animation", a, animation.name);
      for (size_t c = 0; c < animation.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = animation.channels[c];
        std::string what = animation_name + " channel " + std::to_string(c);
        if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
          fail(what + " refers to missing sampler " + std::to_string(channel.sampler));
        int node = channel.target_node;
        if (node < 0 || size_t(node) >= model_.nodes.size()) fail(what + " targets missing node " + std::to_string(node));
        if (channel.target_path == "weights") {
          ++weight_channels;
          continue;
        }
        std::optional<AnimatedProperty> property = animated_property(channel.target_path);
        if (!property) fail(what + " has unknown target path '" + channel.target_path + "'");
        std::string target = quoted_name("node", node, model_.nodes[node].name) + " " + channel.target_path;
        if (!model_.nodes[node].matrix.empty())
          fail(what + " targets " + target + ", but the node has a matrix (glTF animates only TRS nodes)");
        auto [it, fresh] = animated_by.try_emplace({node, *property}, a);
        if (!fresh && it->second == a) fail(what + " targets " + target + ", which another channel of the animation targets");
        if (!fresh) {
          warnings_.add(target + " is animated by " + quoted_name("animation", it->second, model_.animations[it->second].name) +
                        " and " + animation_name + ": the later one is played");
          std::erase_if(out, [&](const AnimationChannel& o) { return o.node == node && o.property == *property; });
          it->second = a;
        }
        std::string sampler = what + " sampler " + std::to_string(channel.sampler);
        out.push_back(read_sampler(animation.samplers[channel.sampler], *property, sampler));
        out.back().name = what;
        out.back().node = node;
      }
    }
    if (weight_channels > 0)
      warnings_.add("animated morph target weights ignored (" + std::to_string(weight_channels) +
                    " channels): the base shape is rendered");
    return out;
  }

  static std::optional<AnimatedProperty> animated_property(const std::string& path) {
    if (path == "translation") return AnimatedProperty::Translation;
    if (path == "rotation") return AnimatedProperty::Rotation;
    if (path == "scale") return AnimatedProperty::Scale;
    return std::nullopt;
  }

  AnimationChannel read_sampler(const tinygltf::AnimationSampler& sampler, AnimatedProperty property,
                                const std::string& what) const {
    constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE,
                  UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, S = TINYGLTF_COMPONENT_TYPE_SHORT,
                  US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    AnimationChannel c;
    c.property = property;
    if (sampler.interpolation == "LINEAR") c.interpolation = Interpolation::Linear;
    else if (sampler.interpolation == "STEP") c.interpolation = Interpolation::Step;
    else if (sampler.interpolation == "CUBICSPLINE") c.interpolation = Interpolation::CubicSpline;
    else fail(what + " has unknown interpolation '" + sampler.interpolation + "'");

    require_types(sampler.input, {F}, false, what + " input");
    c.times = read_accessor<double>(sampler.input, 1, what + " input");
    if (c.times.empty()) fail(what + " input has no keys");
    for (size_t k = 0; k < c.times.size(); ++k) {
      if (!std::isfinite(c.times[k])) fail(what + " input has a non-finite time at key " + std::to_string(k));
      if (k > 0 && !(c.times[k] > c.times[k - 1]))
        fail(what + " input times are not strictly increasing at key " + std::to_string(k) + " (" +
             std::to_string(c.times[k - 1]) + " then " + std::to_string(c.times[k]) + ")");
    }

    bool rotation = property == AnimatedProperty::Rotation;
    int components = rotation ? 4 : 3;
    if (rotation) require_types(sampler.output, {F, B, UB, S, US}, true, what + " output");
    else if (quantization_) require_types(sampler.output, {F, B, UB, S, US}, false, what + " output");
    else require_types(sampler.output, {F}, false, what + " output");
    c.values = read_accessor<double>(sampler.output, components, what + " output");
    size_t per_key = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
    size_t elements = c.values.size() / components;
    if (elements != c.times.size() * per_key)
      fail(what + " output has " + std::to_string(elements) + " elements for " + std::to_string(c.times.size()) +
           " key times (" + interpolation_name(c.interpolation) + " needs " + std::to_string(c.times.size() * per_key) + ")");
    for (size_t i = 0; i < elements; ++i) {
      const double* v = c.values.data() + i * components;
      if (!std::all_of(v, v + components, [](double x) { return std::isfinite(x); }))
        fail(what + " output has a non-finite value at element " + std::to_string(i));
      bool is_value = per_key == 1 || i % 3 == 1;  // not a spline's tangent
      if (rotation && is_value && !(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3] > 0.0))
        fail(what + " output has a zero rotation quaternion at key " + std::to_string(i / per_key));
    }
    return c;
  }

  // The rig: one RigNode per instance that a channel targets or that descends from one (a
  // node instanced twice gets the channels twice). Returns, per instance, its rig node or -1.
  std::vector<int> build_rig_nodes(const std::vector<Instance>& instances, std::vector<AnimationChannel> channels) {
    std::set<int> targets;
    for (const AnimationChannel& c : channels) targets.insert(c.node);
    std::vector<int> rig_node(instances.size(), -1);
    for (size_t i = 0; i < instances.size(); ++i) {  // parents come first
      const Instance& inst = instances[i];
      int moving_parent = inst.parent >= 0 ? rig_node[inst.parent] : -1;
      if (moving_parent < 0 && !targets.count(inst.node)) continue;
      RigNode n = rest_node(inst.node);
      n.parent = moving_parent;
      if (inst.parent >= 0 && moving_parent < 0) n.parent_world = instances[inst.parent].world;
      rig_node[i] = int(rig_.nodes.size());
      rig_.nodes.push_back(std::move(n));
      for (const AnimationChannel& c : channels)
        if (c.node == inst.node) {
          rig_.channels.push_back(c);
          rig_.channels.back().node = rig_node[i];
        }
    }
    return rig_node;
  }

  // Channels whose nodes are not in the rendered scene move nothing: no animation then.
  void attach_animation() {
    if (rig_.channels.empty()) return;
    rig_.vertex_count = scene_.positions.size();
    std::vector<char> moves(scene_.positions.size(), 0);
    for (const AnimatedMesh& m : rig_.meshes) std::fill_n(moves.begin() + m.first_vertex, m.positions.size(), 1);
    for (size_t v = 0; v < moves.size(); ++v)
      if (!moves[v]) rig_.static_bounds.extend(scene_.positions[v]);
    scene_.animation = std::make_shared<const SceneAnimation>(std::move(rig_));
  }

  // ---- accessors ----

  static int component_size(int type) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
      case TINYGLTF_COMPONENT_TYPE_SHORT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
      case TINYGLTF_COMPONENT_TYPE_INT:
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
      default: return 0;
    }
  }

  // Integers decode per the glTF rules for normalized values (signed ones clamp at -1).
  static double load_component(const unsigned char* p, int type, bool normalized) {
    auto get = [p](auto v) { std::memcpy(&v, p, sizeof v); return v; };
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE: { double v = get(int8_t()); return normalized ? std::max(v / 127.0, -1.0) : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { double v = get(uint8_t()); return normalized ? v / 255.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_SHORT: { double v = get(int16_t()); return normalized ? std::max(v / 32767.0, -1.0) : v; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { double v = get(uint16_t()); return normalized ? v / 65535.0 : v; }
      case TINYGLTF_COMPONENT_TYPE_INT: return get(int32_t());
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return get(uint32_t());
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return get(float());
      default: return 0.0;
    }
  }

  // Start of `count` elements of `element` bytes, `stride` apart, at `offset` in a bufferView;
  // every byte is checked to lie inside the view and the view inside its buffer.
  const unsigned char* checked_bytes(int view_index, size_t offset, size_t element, size_t stride, size_t count,
                                     const std::string& what) const {
    if (view_index < 0 || size_t(view_index) >= model_.bufferViews.size())
      fail(what + " refers to missing bufferView " + std::to_string(view_index));
    const tinygltf::BufferView& view = model_.bufferViews[view_index];
    std::string view_name = "bufferView " + std::to_string(view_index);
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
      fail(view_name + " refers to missing buffer " + std::to_string(view.buffer));
    const tinygltf::Buffer& buffer = model_.buffers[view.buffer];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
      fail("buffer " + std::to_string(view.buffer) + " is too short for " + view_name + " (needs " +
           std::to_string(view.byteOffset + view.byteLength) + " bytes, has " + std::to_string(buffer.data.size()) + ")");
    if (count > 0) {
      size_t len = view.byteLength;
      bool fits = offset <= len && element <= len - offset && (count - 1) <= (len - offset - element) / std::max<size_t>(stride, 1);
      if (!fits) {
        // In long double and printed from it: the sum may exceed 2^64 (a byteOffset of 2^64-1),
        // where a cast back to an integer is undefined.
        long double needed = (long double)offset + (long double)(count - 1) * stride + element;
        char needed_text[64];
        std::snprintf(needed_text, sizeof needed_text, "%.0Lf", needed);
        fail(what + " reaches beyond " + view_name + " (needs " + needed_text + " bytes, has " + std::to_string(len) + ")");
      }
    }
    return buffer.data.data() + view.byteOffset + offset;
  }

  const tinygltf::Accessor& accessor(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size()) fail(what + " refers to missing accessor " + std::to_string(index));
    return model_.accessors[index];
  }

  // Without a bufferView nothing in the file bounds an accessor's count (its data is implicit
  // zeros), so the elements of all such accessors together are bounded before any is read: 40 of
  // them in a 4.6 KB file could otherwise ask for 30 GB.
  void check_implicit_accessors() const {
    size_t total = 0;
    for (size_t i = 0; i < model_.accessors.size(); ++i) {
      const tinygltf::Accessor& a = model_.accessors[i];
      if (a.bufferView >= 0) continue;
      total += std::min(a.count, kMaxImplicitElements + 1);
      if (total > kMaxImplicitElements)
        fail("accessor " + std::to_string(i) + " has no bufferView and count " + std::to_string(a.count) +
             ": accessors without data may hold at most " + std::to_string(kMaxImplicitElements) + " elements in all");
    }
  }

  // count x components numbers of an accessor, normalisation and sparse substitution applied.
  template <class T>
  std::vector<T> read_accessor(int index, int components, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    std::string where = what + " (accessor " + std::to_string(index) + ")";
    int size = component_size(a.componentType);
    if (size == 0) fail(where + " has invalid componentType " + std::to_string(a.componentType));
    if (tinygltf::GetNumComponentsInType(a.type) != components)
      fail(where + " has " + std::to_string(tinygltf::GetNumComponentsInType(a.type)) + " components per element (needs " +
           std::to_string(components) + ")");
    size_t element = size_t(size) * components;
    // (An accessor without a bufferView has a count bounded by check_implicit_accessors.)
    const unsigned char* p = nullptr;
    size_t stride = element;
    if (a.bufferView >= 0) {
      if (size_t(a.bufferView) < model_.bufferViews.size() && model_.bufferViews[a.bufferView].byteStride > 0)
        stride = model_.bufferViews[a.bufferView].byteStride;
      p = checked_bytes(a.bufferView, a.byteOffset, element, stride, a.count, where);
    }
    std::vector<T> out(a.count * components, T(0));
    if (p) {
      for (size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < components; ++c)
          out[i * components + c] = T(load_component(p + i * stride + size_t(c) * size, a.componentType, a.normalized));
    }
    if (a.sparse.isSparse) apply_sparse(a, size, components, where, out);
    return out;
  }

  template <class T>
  void apply_sparse(const tinygltf::Accessor& a, int size, int components, const std::string& where,
                    std::vector<T>& out) const {
    if (a.sparse.count < 0) fail(where + " has a negative sparse count");
    size_t n = size_t(a.sparse.count);
    int index_type = a.sparse.indices.componentType;
    int index_size = component_size(index_type);
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(where + " has sparse indices of invalid componentType " + std::to_string(index_type));
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) fail(where + " has a negative sparse byteOffset");
    size_t element = size_t(size) * components;
    const unsigned char* idx = checked_bytes(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, index_size,
                                             index_size, n, where + " sparse indices");
    const unsigned char* val = checked_bytes(a.sparse.values.bufferView, a.sparse.values.byteOffset, element, element, n,
                                             where + " sparse values");
    for (size_t k = 0; k < n; ++k) {
      double target = load_component(idx + k * index_size, index_type, false);
      if (target >= double(a.count))
        fail(where + " sparse index " + std::to_string((unsigned long long)target) + " >= count " + std::to_string(a.count));
      for (int c = 0; c < components; ++c)
        out[size_t(target) * components + c] =
            T(load_component(val + k * element + size_t(c) * size, a.componentType, a.normalized));
    }
  }

  void require_types(int index, std::initializer_list<int> allowed, bool normalized_only, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    for (int t : allowed)
      if (a.componentType == t && (!normalized_only || a.normalized || t == TINYGLTF_COMPONENT_TYPE_FLOAT)) return;
    fail(what + " (accessor " + std::to_string(index) + ") has unsupported componentType " + std::to_string(a.componentType) +
         (a.normalized ? " (normalized)" : ""));
  }

  // Decoded float attributes are cached: meshes are often instanced, and exporters let many
  // primitives share one vertex accessor.
  const std::vector<float>& float_attribute(int index, int components, const std::string& semantic,
                                            const std::string& what) {
    auto it = float_cache_.find(index);
    if (it != float_cache_.end()) return it->second;
    std::vector<float> values = read_accessor<float>(index, components, what + " " + semantic);
    for (size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        fail(what + " " + semantic + " has a non-finite value (NaN or Inf) at vertex " + std::to_string(i / components));
    return float_cache_.emplace(index, std::move(values)).first->second;
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
      if (!(draco && draco->attributes.count(semantic))) require_types(index, allowed, normalized_only, what + " " + semantic);
    };
    auto values = [&](int index, int components, const char* semantic) -> const std::vector<float>* {
      if (draco && draco->attributes.count(semantic)) {
        if (draco->components.at(semantic) != components)
          fail(what + " Draco attribute " + semantic + " has " + std::to_string(draco->components.at(semantic)) +
               " components (needs " + std::to_string(components) + ")");
        return &draco->attributes.at(semantic);
      }
      return &float_attribute(index, components, semantic, what);
    };
    Attributes at;
    int pos = prim.attributes.at("POSITION");
    if (quantization_) require(pos, {F, B, UB, S, US}, false, "POSITION");
    else require(pos, {F}, false, "POSITION");
    at.positions = values(pos, 3, "POSITION");
    at.count = at.positions->size() / 3;
    auto same_count = [&](const std::vector<float>& v, size_t comps, const char* semantic) {
      if (v.size() / comps != at.count)
        fail(what + " " + semantic + " has " + std::to_string(v.size() / comps) + " elements but POSITION has " +
             std::to_string(at.count));
    };
    if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
      if (quantization_) require(it->second, {F, B, S}, true, "NORMAL");
      else require(it->second, {F}, false, "NORMAL");
      at.normals = values(it->second, 3, "NORMAL");
      same_count(*at.normals, 3, "NORMAL");
    }
    const std::string texcoord = "TEXCOORD_" + std::to_string(uv_set);
    if (auto it = prim.attributes.find(texcoord); it != prim.attributes.end()) {
      if (quantization_) require(it->second, {F, B, UB, S, US}, false, texcoord.c_str());
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
        const tinygltf::Accessor& a = accessor(it->second, what + " COLOR_0");
        at.color_components = a.type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
      }
      at.colors = values(it->second, at.color_components, "COLOR_0");
      same_count(*at.colors, size_t(at.color_components), "COLOR_0");
      uses_.insert("COLOR_0");
    }
    if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end()) {
      if (quantization_) require(it->second, {F, B, S}, true, "TANGENT");
      else require(it->second, {F}, false, "TANGENT");
      at.tangents = values(it->second, 4, "TANGENT");
      same_count(*at.tangents, 4, "TANGENT");
      uses_.insert("TANGENT");
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
    require_types(prim.indices,
                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                  false, what + " indices");
    idx = read_accessor<uint32_t>(prim.indices, 1, what + " indices");
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
      if (n % 3 != 0) warnings_.add("index count not a multiple of 3: trailing indices ignored");
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

  // The primitive's KHR_draco_mesh_compression data decoded (once per bufferView: instanced meshes
  // share it), or null without the extension.
  const DracoPrimitive* draco_primitive(const tinygltf::Primitive& prim, const std::string& what) {
    const tinygltf::Value* ext = extension(prim.extensions, "KHR_draco_mesh_compression");
    if (!ext) return nullptr;
    const double view = number_or(member(*ext, "bufferView"), -1.0);
    const tinygltf::Value* attributes = member(*ext, "attributes");
    if (!(view >= 0.0 && view < double(model_.bufferViews.size()) && view == std::floor(view)))
      fail(what + " has a KHR_draco_mesh_compression without a valid bufferView");
    if (!attributes || !attributes->IsObject())
      fail(what + " has a KHR_draco_mesh_compression without attributes");
    const int view_index = int(view);
    if (auto it = draco_cache_.find(view_index); it != draco_cache_.end()) return &it->second;
    std::map<std::string, DracoAttributeRequest> requests;
    for (const std::string& semantic : attributes->Keys()) {
      const double id = number_or(&attributes->Get(semantic), -1.0);
      if (!(id >= 0.0 && id <= double(INT32_MAX) && id == std::floor(id)))
        fail(what + " has a KHR_draco_mesh_compression attribute " + semantic + " that is not a whole number");
      DracoAttributeRequest& r = requests[semantic];
      r.unique_id = int(id);
      if (auto a = prim.attributes.find(semantic); a != prim.attributes.end())
        r.normalized = accessor(a->second, what + " " + semantic).normalized;
    }
    const size_t length = model_.bufferViews[view_index].byteLength;
    const unsigned char* bytes = checked_bytes(view_index, 0, length, 1, 1, what + " Draco data");
    uses_.insert("KHR_draco_mesh_compression");
    return &draco_cache_.emplace(view_index, decode_draco_primitive(bytes, length, requests, file_ + ": " + what))
                .first->second;
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
      warnings_.add(name ? std::string(name) + " primitives skipped (only triangles are rendered)"
                         : "primitives of unknown mode " + std::to_string(mode) + " skipped");
      return;
    }
    if (!prim.attributes.count("POSITION")) {
      warnings_.add("primitives without POSITION skipped");
      return;
    }
    if (!prim.targets.empty()) warnings_.add("morph targets ignored: the base shape is rendered");
    int gltf_material = prim.material;
    if (gltf_material >= int(model_.materials.size())) fail(what + " refers to missing material " + std::to_string(gltf_material));
    uint32_t material = gltf_material < 0 ? uint32_t(model_.materials.size()) : uint32_t(gltf_material);

    const UvMapping& uv = material_uv_mapping(gltf_material);
    const DracoPrimitive* draco = draco_primitive(prim, what);
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
      warnings_.add("zero-length vertex normals replaced by the geometric normal");
    }
  }

  // glTF: without NORMAL, a primitive is flat shaded; each triangle gets its own three vertices.
  void append_flat(const Attributes& at, const std::vector<uvec3>& tris, const glm::dmat4& world, uint32_t material,
                   const std::string& what) {
    warnings_.add("primitives without NORMAL: flat normals generated");
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
      warnings_.add("camera '" + name + "' is " + (cam.type.empty() ? "untyped" : cam.type) + ": skipped (only perspective cameras)");
      return;
    }
    double yfov = cam.perspective.yfov, aspect = cam.perspective.aspectRatio;
    if (!(yfov > 0.0 && yfov < kPi)) fail("camera '" + name + "' has yfov " + std::to_string(yfov) + " (must be in (0, pi))");
    if (!(aspect >= 0.0 && std::isfinite(aspect))) fail("camera '" + name + "' has aspectRatio " + std::to_string(aspect));
    Camera c;
    if (!place_camera(inst.world, c)) {
      warnings_.add("camera '" + name + "' has a degenerate node transform: skipped");
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
      warnings_.add(what + " has unknown type '" + l.type + "': skipped");
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
    if (l.range > 0.0) warnings_.add("light range ignored: pure inverse-square falloff, as in the references");
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
      warnings_.add(what + " cone angles outside 0 <= inner <= outer <= pi/2: clamped");
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
    warnings_.add("scene has no perspective camera: added camera 'auto' framing the bounding box from +Z");
  }

  bool scene_has_lights() const {
    if (!scene_.lights.empty()) return true;
    for (uint32_t m : scene_.triangle_material)
      if (scene_.material_emits(m)) return true;
    return false;
  }

  // ---- materials and textures ----

  void build_materials() {
    std::vector<char> used(model_.materials.size() + 1, 0);
    for (uint32_t m : scene_.triangle_material) used[m] = 1;
    for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(convert_material(int(i), used[i]));
    if (used.back()) {
      Material def;  // glTF's default material: white, metallic 1, roughness 1
      def.name = "default";
      scene_.materials.push_back(def);
    }
  }

  vec3 factor3(const std::vector<double>& v, size_t expected, vec3 fallback, const std::string& what) const {
    if (v.empty()) return fallback;
    if (v.size() != expected) fail(what + " has " + std::to_string(v.size()) + " numbers (needs " + std::to_string(expected) + ")");
    if (!all_finite(v)) fail(what + " is not finite");
    return vec3(float(v[0]), float(v[1]), float(v[2]));
  }

  float unit_factor(double v, const std::string& what) {
    if (!std::isfinite(v)) fail(what + " is not finite");
    if (v < 0.0 || v > 1.0) warnings_.add(what + " outside [0, 1]: clamped");
    return float(std::clamp(v, 0.0, 1.0));
  }

  static double emissive_strength(const tinygltf::Material& g) {
    const tinygltf::Value* ext = extension(g.extensions, "KHR_materials_emissive_strength");
    return number_or(ext ? member(*ext, "emissiveStrength") : nullptr, 1.0);
  }

  // Unused materials keep their factors but no textures, so that unused images are never read.
  Material convert_material(int index, bool used) {
    const tinygltf::Material& g = model_.materials[index];
    std::string what = "material '" + (g.name.empty() ? std::to_string(index) : g.name) + "'";
    const auto& pbr = g.pbrMetallicRoughness;
    Material out;
    out.name = g.name.empty() ? "material" + std::to_string(index) : g.name;
    vec3 base = factor3(pbr.baseColorFactor, 4, vec3(1.0f), what + " baseColorFactor");
    if (glm::any(glm::lessThan(base, vec3(0.0f))) || glm::any(glm::greaterThan(base, vec3(1.0f))))
      warnings_.add(what + " baseColorFactor outside [0, 1]: clamped");
    out.base_color = glm::clamp(base, vec3(0.0f), vec3(1.0f));
    out.metallic = unit_factor(pbr.metallicFactor, what + " metallicFactor");
    out.roughness = unit_factor(pbr.roughnessFactor, what + " roughnessFactor");
    out.emission = factor3(g.emissiveFactor, 3, vec3(0.0f), what + " emissiveFactor") * float(emissive_strength(g));
    if (!is_finite(out.emission) || glm::any(glm::lessThan(out.emission, vec3(0.0f))))
      fail(what + " has a negative or non-finite emission (emissiveFactor * emissiveStrength)");
    out.double_sided = g.doubleSided;
    out.alpha = pbr.baseColorFactor.size() == 4 ? unit_factor(pbr.baseColorFactor[3], what + " baseColorFactor alpha") : 1.0f;
    if (g.alphaMode == "MASK") {
      out.alpha_mode = AlphaMode::Mask;
      if (!std::isfinite(g.alphaCutoff) || g.alphaCutoff < 0.0)
        fail(what + " has alphaCutoff " + std::to_string(g.alphaCutoff) + " (must be a number >= 0)");
      out.alpha_cutoff = float(g.alphaCutoff);
    } else if (g.alphaMode == "BLEND") {
      out.alpha_mode = AlphaMode::Blend;
    } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
      fail(what + " has alphaMode '" + g.alphaMode + "' (must be OPAQUE, MASK or BLEND)");
    }
    if (used && out.alpha_mode != AlphaMode::Opaque)
      uses_.insert(out.alpha_mode == AlphaMode::Mask ? "alphaMode MASK" : "alphaMode BLEND (as a cutout at 0.5)");
    if (used) attach_textures(g, what, out);
    return out;
  }

  void attach_textures(const tinygltf::Material& g, const std::string& what, Material& out) {
    if (g.occlusionTexture.index >= 0) warnings_.add("occlusion textures are ignored (they model what GI computes)");
    for (const auto& [name, value] : g.extensions)  // those in extensionsUsed were reported already
      if (!contains(kImplementedExtensions, name) && !contains(model_.extensionsUsed, std::string_view(name)))
        warnings_.add("material extension " + name + " ignored");
    const auto& pbr = g.pbrMetallicRoughness;
    out.base_color_texture = texture_slot(pbr.baseColorTexture, true, what + " baseColorTexture");
    out.metallic_roughness_texture = texture_slot(pbr.metallicRoughnessTexture, false, what + " metallicRoughnessTexture");
    out.emissive_texture = texture_slot(g.emissiveTexture, true, what + " emissiveTexture");
    out.normal_texture = texture_slot(as_texture_info(g.normalTexture), false, what + " normalTexture");
    if (out.normal_texture >= 0) {
      if (!std::isfinite(g.normalTexture.scale)) fail(what + " has a non-finite normalTexture scale");
      out.normal_scale = float(g.normalTexture.scale);
      uses_.insert("normalTexture");
    }
  }

  static tinygltf::TextureInfo as_texture_info(const tinygltf::NormalTextureInfo& n) {
    tinygltf::TextureInfo t;
    t.index = n.index;
    t.texCoord = n.texCoord;
    t.extensions = n.extensions;
    return t;
  }

  // The UV set and KHR_texture_transform of one texture reference, checked.
  UvMapping texture_uv_mapping(const tinygltf::TextureInfo& info, const std::string& what) const {
    UvMapping m;
    m.set = info.texCoord;
    const tinygltf::Value* t = extension(info.extensions, "KHR_texture_transform");
    if (t) {
      auto pair = [&](const char* key, double fallback) {
        const tinygltf::Value* v = member(*t, key);
        if (v && (!v->IsArray() || v->ArrayLen() != 2)) fail(what + " has a KHR_texture_transform " + key + " that is not 2 numbers");
        return glm::dvec2(number_or(v ? &v->Get(0) : nullptr, fallback), number_or(v ? &v->Get(1) : nullptr, fallback));
      };
      const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
      const double rotation = number_or(member(*t, "rotation"), 0.0);
      if (!std::isfinite(offset.x + offset.y + scale.x + scale.y + rotation))
        fail(what + " has a non-finite KHR_texture_transform");
      if (const tinygltf::Value* set = member(*t, "texCoord")) {
        const double d = number_or(set, -1.0);  // checked before the conversion, which could overflow
        m.set = d >= 0.0 && d <= kMaxUvSet && d == std::floor(d) ? int(d) : -1;
      }
      // KHR_texture_transform: scale, then rotate (u' = u cos + v sin, v' = v cos - u sin), then offset.
      const double c = std::cos(rotation), s = std::sin(rotation);
      m.u = {scale.x * c, scale.y * s, offset.x};
      m.v = {-scale.x * s, scale.y * c, offset.y};
    }
    if (m.set < 0 || m.set > kMaxUvSet) fail(what + " has a texCoord that is not a whole number in 0.." + std::to_string(kMaxUvSet));
    return m;
  }

  // One UV mapping per material, applied to its vertices when they are loaded (exact: the
  // transform is affine, so it commutes with the interpolation over a triangle): that of its
  // baseColorTexture, else of its first other texture. Textures of one material that disagree
  // keep the first's, with a warning.
  const UvMapping& material_uv_mapping(int gltf_material) {
    auto [it, fresh] = uv_mappings_.try_emplace(gltf_material);
    if (!fresh || gltf_material < 0 || size_t(gltf_material) >= model_.materials.size()) return it->second;
    const tinygltf::Material& g = model_.materials[gltf_material];
    const std::string what = quoted_name("material", gltf_material, g.name);
    const tinygltf::TextureInfo normal = as_texture_info(g.normalTexture);
    const std::pair<const tinygltf::TextureInfo*, const char*> slots[] = {
        {&g.pbrMetallicRoughness.baseColorTexture, " baseColorTexture"},
        {&g.pbrMetallicRoughness.metallicRoughnessTexture, " metallicRoughnessTexture"},
        {&g.emissiveTexture, " emissiveTexture"},
        {&normal, " normalTexture"}};
    bool first = true;
    for (const auto& [info, slot] : slots) {
      if (info->index < 0) continue;
      UvMapping m = texture_uv_mapping(*info, what + slot);
      if (first) it->second = m;
      else if (!(m == it->second))
        warnings_.add("textures of one material with different UV sets or transforms: the first's used for all");
      first = false;
    }
    if (!it->second.affine_identity()) uses_.insert("KHR_texture_transform");
    if (it->second.set > 0) uses_.insert("TEXCOORD_" + std::to_string(it->second.set));
    return it->second;
  }

  int texture_slot(const tinygltf::TextureInfo& info, bool srgb, const std::string& what) {
    if (info.index < 0) return -1;
    if (size_t(info.index) >= model_.textures.size()) fail(what + " refers to missing texture " + std::to_string(info.index));
    const tinygltf::Texture& tex = model_.textures[info.index];
    if (tex.source < 0) {
      warnings_.add("textures without a core image source (e.g. KTX2/WebP extensions) ignored");
      return -1;
    }
    if (size_t(tex.source) >= model_.images.size()) fail(what + " refers to missing image " + std::to_string(tex.source));
    if (tex.sampler >= int(model_.samplers.size())) fail(what + " refers to missing sampler " + std::to_string(tex.sampler));
    TextureKey key{tex.source, srgb, std::max(tex.sampler, -1)};
    auto [it, fresh] = texture_slots_.try_emplace(key, int(texture_keys_.size()));
    if (fresh) texture_keys_.push_back(key);
    return it->second;
  }

  std::string image_label(int index) const {
    const tinygltf::Image& img = model_.images[index];
    if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) return "'" + img.uri + "'";
    return quoted_name("image", index, img.name);
  }

  // The encoded bytes of an image: from its file or data URI (kept by keep_encoded_image), or
  // from its bufferView, bounds-checked.
  std::pair<const unsigned char*, size_t> encoded_image(int index) const {
    const tinygltf::Image& img = model_.images[index];
    if (img.bufferView >= 0) {
      size_t len = size_t(img.bufferView) < model_.bufferViews.size() ? model_.bufferViews[img.bufferView].byteLength : 0;
      return {checked_bytes(img.bufferView, 0, len, 1, 1, "image " + std::to_string(index)), len};
    }
    if (img.image.empty()) fail("image " + image_label(index) + " not found, empty or not a regular file");
    return {img.image.data(), img.image.size()};
  }

  // glTF 2.0 allows PNG and JPEG only; stb would also read other formats, some of them wrongly
  // (16-bit PNM), so anything else is refused rather than risk a silently wrong texture.
  void require_png_or_jpeg(int index, std::pair<const unsigned char*, size_t> bytes) const {
    auto [p, n] = bytes;
    bool png = n >= 8 && std::memcmp(p, "\x89PNG\r\n\x1a\n", 8) == 0;
    bool jpeg = n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF;
    if (!png && !jpeg) fail("image " + image_label(index) + " is neither PNG nor JPEG (the formats glTF 2.0 allows)");
  }

  // Images decode in parallel (stb via tinygltf), then each (image, colour space, sampler)
  // becomes one float texture, also in parallel.
  void decode_textures() {
    std::vector<int> image_ids;
    for (const TextureKey& k : texture_keys_)
      if (std::find(image_ids.begin(), image_ids.end(), k.image) == image_ids.end()) image_ids.push_back(k.image);
    std::vector<std::pair<const unsigned char*, size_t>> encoded;
    uint64_t decoded_bytes = 0;
    const uint64_t budget = usable_memory_bytes() / 4;
    for (int id : image_ids) {
      encoded.push_back(encoded_image(id));
      require_png_or_jpeg(id, encoded.back());
      // The header's size is checked before stb allocates it (decompression bombs), and a JPEG's
      // Huffman tables before stb indexes them (see encoded_image.h).
      EncodedImageHeader header;
      if (std::string why = read_encoded_image_header(encoded.back().first, encoded.back().second, header); !why.empty())
        fail("cannot decode image " + image_label(id) + ": " + why);
      if (header.width > kMaxTextureSide || header.height > kMaxTextureSide)
        fail("image " + image_label(id) + " is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
             " pixels: textures may have at most " + std::to_string(kMaxTextureSide) + " per side");
      // Decoded as stored, then converted to RGBA: 8-bit to 4 bytes a texel, 16-bit to 16.
      decoded_bytes += uint64_t(header.width) * uint64_t(header.height) *
                       uint64_t(header.channels * header.bytes_per_channel + (header.bytes_per_channel == 2 ? 16 : 4));
      if (decoded_bytes > budget)
        fail("the textures up to image " + image_label(id) + " need " + std::to_string(decoded_bytes >> 20) +
             " MiB decoded, more than a quarter of this machine's memory (" + std::to_string(usable_memory_bytes() >> 20) + " MiB)");
    }
    std::vector<tinygltf::Image> decoded(image_ids.size());
    std::vector<std::string> errors(image_ids.size());
    tbb::parallel_for(size_t(0), image_ids.size(), [&](size_t i) {
      std::string err, warn;
      auto [bytes, size] = encoded[i];
      if (size > size_t(INT32_MAX)) err = "image larger than 2 GiB";
      else if (!tinygltf::LoadImageData(&decoded[i], image_ids[i], &err, &warn, 0, 0, bytes, int(size), nullptr))
        // tinygltf's own text only says "unsupported image format"; stb's reason (a thread-local
        // of this thread, which just decoded) says what is wrong. Some corrupt PNGs leave that
        // reason empty, and an empty error here once let the undecoded image through (fuzzing).
        err = stbi_failure_reason() && *stbi_failure_reason() ? stbi_failure_reason() : "cannot decode";
      else if (!valid_decoded(decoded[i]))
        err = "unsupported pixel layout (" + std::to_string(decoded[i].component) + " channels, " +
              std::to_string(decoded[i].bits) + " bits)";
      errors[i] = err;
    });
    for (size_t i = 0; i < image_ids.size(); ++i)
      if (!errors[i].empty()) fail("cannot decode image " + image_label(image_ids[i]) + ": " + first_line(errors[i]));
    std::vector<size_t> slot_of_key(texture_keys_.size());
    for (size_t k = 0; k < texture_keys_.size(); ++k)
      slot_of_key[k] = std::find(image_ids.begin(), image_ids.end(), texture_keys_[k].image) - image_ids.begin();
    scene_.textures.resize(texture_keys_.size());
    tbb::parallel_for(size_t(0), texture_keys_.size(), [&](size_t k) {
      scene_.textures[k] = to_texture(decoded[slot_of_key[k]], texture_keys_[k].srgb);
    });
    for (size_t k = 0; k < texture_keys_.size(); ++k) apply_sampler(texture_keys_[k].sampler, scene_.textures[k]);
  }

  void apply_sampler(int sampler, Texture& t) {
    if (sampler < 0) return;  // glTF: no sampler = repeat, auto filtering
    const tinygltf::Sampler& s = model_.samplers[sampler];
    t.wrap_s = wrap_mode(s.wrapS, warnings_);
    t.wrap_t = wrap_mode(s.wrapT, warnings_);
    t.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
  }

  // The largest texture side GPUs accept; larger ones are refused before decoding.
  static constexpr int kMaxTextureSide = 16384;
  const tinygltf::Model& model_;
  const std::string& file_;
  Scene& scene_;
  Warnings warnings_;
  AnimationRig rig_;
  AnimatedMesh* recording_ = nullptr;  // the moving mesh whose object-space vertices are kept
  bool quantization_ = false;
  size_t degenerate_triangles_ = 0;
  std::unordered_map<int, std::vector<float>> float_cache_;
  static constexpr size_t kMaxImplicitElements = size_t(1) << 24;
  std::map<TextureKey, int> texture_slots_;
  std::map<int, UvMapping> uv_mappings_;  // by glTF material
  std::set<std::string> uses_;            // Scene::gltf_features
  std::map<int, DracoPrimitive> draco_cache_;  // by bufferView
  std::vector<TextureKey> texture_keys_;
};

uint32_t little_endian32(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | uint8_t(bytes[at + size_t(i)]);
  return v;
}

// The JSON chunk of a GLB, after checking its 12-byte header and the lengths of its chunks
// against the file. tinygltf 2.7 (Debian 12) compares the BIN chunk's length with the file
// without counting the chunk's 8-byte header, so a BIN chunk up to 8 bytes too long is read past
// the end of the buffer; nothing too long gets to it now.
std::string_view checked_glb_json(std::string_view bytes, const std::string& name) {
  auto fail = [&](const std::string& problem) -> std::string_view { throw Error(name + ": invalid GLB: " + problem); };
  if (bytes.size() < 20) return fail("shorter than its 12-byte header and a chunk header");
  if (uint32_t version = little_endian32(bytes, 4); version != 2) return fail("version " + std::to_string(version) + " (glTF 2.0 is version 2)");
  if (uint32_t length = little_endian32(bytes, 8); length != bytes.size())
    return fail("header says " + std::to_string(length) + " bytes, the file has " + std::to_string(bytes.size()));
  uint64_t json_length = little_endian32(bytes, 12);
  if (little_endian32(bytes, 16) != 0x4E4F534Au) return fail("the first chunk is not JSON");
  if (json_length == 0 || 20 + json_length > bytes.size())
    return fail("JSON chunk of " + std::to_string(json_length) + " bytes in a file of " + std::to_string(bytes.size()));
  uint64_t at = 20 + json_length;
  while (at < bytes.size()) {  // the BIN chunk, and any later chunk (which readers must skip)
    if (bytes.size() - at < 8) return fail("truncated chunk header at byte " + std::to_string(at));
    uint64_t chunk_length = little_endian32(bytes, at);
    if (chunk_length > bytes.size() - at - 8)
      return fail("chunk at byte " + std::to_string(at) + " declares " + std::to_string(chunk_length) + " bytes, " +
                  std::to_string(bytes.size() - at - 8) + " follow");
    at += 8 + chunk_length;
  }
  return bytes.substr(20, json_length);
}

// What tinygltf would mishandle in the JSON itself: nesting deep enough to overflow its
// recursive conversion of extras/extensions, and an empty buffer, which it copies with
// vector::at(0) (glTF requires byteLength >= 1).
void check_gltf_json(std::string_view json_text, const std::string& name) {
  require_json_depth(json_text, name);
  nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;  // tinygltf reports malformed JSON itself
  auto buffers = j.find("buffers");
  if (buffers == j.end() || !buffers->is_array()) return;
  for (size_t i = 0; i < buffers->size(); ++i) {
    const nlohmann::json& b = (*buffers)[i];
    auto length = b.is_object() ? b.find("byteLength") : b.end();
    if (length != b.end() && length->is_number() && !(length->get<double>() >= 1.0))
      throw Error(name + ": buffer " + std::to_string(i) + " has byteLength " + length->dump() + " (glTF requires >= 1)");
  }
}

// tinygltf 2.8 refuses a primitive whose indices accessor has no bufferView, which is how
// KHR_draco_mesh_compression declares them (the indices are in the Draco data): such primitives
// lose their "indices" before tinygltf sees the JSON, and the loader takes them from Draco. The
// JSON text to hand tinygltf, when it changes.
std::optional<std::string> without_draco_index_accessors(std::string_view json_text) {
  nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return std::nullopt;
  const nlohmann::json* accessors = j.contains("accessors") && j["accessors"].is_array() ? &j["accessors"] : nullptr;
  bool changed = false;
  for (nlohmann::json& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("indices") || !prim.contains("extensions") ||
          !prim["extensions"].is_object() || !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      const nlohmann::json& index = prim["indices"];
      const bool listed = accessors && index.is_number_unsigned() && index.get<uint64_t>() < accessors->size();
      if (listed && (*accessors)[index.get<size_t>()].is_object() && (*accessors)[index.get<size_t>()].contains("bufferView"))
        continue;
      prim.erase("indices");
      changed = true;
    }
  }
  if (!changed) return std::nullopt;
  return j.dump();
}

// A GLB with its JSON chunk replaced by `json_text` (the BIN chunk and anything after it kept).
std::string glb_with_json(std::string_view glb, std::string_view old_json, std::string json_text) {
  while (json_text.size() % 4) json_text.push_back(' ');
  std::string out(glb.substr(0, 12));
  auto put32 = [&](uint32_t v, size_t at) { std::memcpy(out.data() + at, &v, 4); };
  const std::string_view rest = glb.substr(std::min(glb.size(), 20 + old_json.size()));
  out += std::string(8, '\0');
  put32(uint32_t(json_text.size()), 12);
  put32(0x4E4F534Au, 16);  // "JSON"
  out += json_text;
  out += rest;
  put32(uint32_t(out.size()), 8);
  return out;
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

}  // namespace

Scene load_gltf_from_memory(std::string_view bytes, const std::string& base_dir, const std::string& name) {
  tinygltf::Model model = parse(bytes, base_dir, name);
  Scene scene;
  scene.source = name;
  GltfConverter(model, name, scene).run();
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
