#include "core/scene/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>

namespace sst::gltf {
namespace {

std::optional<AnimatedProperty> animated_property(const std::string& path) {
  if (path == "translation") return AnimatedProperty::Translation;
  if (path == "rotation") return AnimatedProperty::Rotation;
  if (path == "scale") return AnimatedProperty::Scale;
  return std::nullopt;
}

AnimationChannel read_sampler(const Context& ctx, const Accessors& accessors, const tinygltf::AnimationSampler& sampler,
                              AnimatedProperty property, const std::string& what) {
  constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE,
                UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, S = TINYGLTF_COMPONENT_TYPE_SHORT,
                US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  AnimationChannel c;
  c.property = property;
  if (sampler.interpolation == "LINEAR") c.interpolation = Interpolation::Linear;
  else if (sampler.interpolation == "STEP") c.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE") c.interpolation = Interpolation::CubicSpline;
  else ctx.fail(what + " has unknown interpolation '" + sampler.interpolation + "'");

  accessors.require_types(sampler.input, {F}, false, what + " input");
  c.times = accessors.read<double>(sampler.input, 1, what + " input");
  if (c.times.empty()) ctx.fail(what + " input has no keys");
  for (size_t k = 0; k < c.times.size(); ++k) {
    if (!std::isfinite(c.times[k])) ctx.fail(what + " input has a non-finite time at key " + std::to_string(k));
    if (k > 0 && !(c.times[k] > c.times[k - 1]))
      ctx.fail(what + " input times are not strictly increasing at key " + std::to_string(k) + " (" +
               std::to_string(c.times[k - 1]) + " then " + std::to_string(c.times[k]) + ")");
  }

  bool rotation = property == AnimatedProperty::Rotation;
  int components = rotation ? 4 : 3;
  if (rotation) accessors.require_types(sampler.output, {F, B, UB, S, US}, true, what + " output");
  else if (ctx.quantization) accessors.require_types(sampler.output, {F, B, UB, S, US}, false, what + " output");
  else accessors.require_types(sampler.output, {F}, false, what + " output");
  c.values = accessors.read<double>(sampler.output, components, what + " output");
  size_t per_key = c.interpolation == Interpolation::CubicSpline ? 3 : 1;
  size_t elements = c.values.size() / components;
  if (elements != c.times.size() * per_key)
    ctx.fail(what + " output has " + std::to_string(elements) + " elements for " + std::to_string(c.times.size()) +
             " key times (" + interpolation_name(c.interpolation) + " needs " + std::to_string(c.times.size() * per_key) + ")");
  for (size_t i = 0; i < elements; ++i) {
    const double* v = c.values.data() + i * components;
    if (!std::all_of(v, v + components, [](double x) { return std::isfinite(x); }))
      ctx.fail(what + " output has a non-finite value at element " + std::to_string(i));
    bool is_value = per_key == 1 || i % 3 == 1;  // not a spline's tangent
    if (rotation && is_value && !(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3] > 0.0))
      ctx.fail(what + " output has a zero rotation quaternion at key " + std::to_string(i / per_key));
  }
  return c;
}

}  // namespace

std::vector<AnimationChannel> read_animations(Context& ctx, const Accessors& accessors) {
  const tinygltf::Model& model = ctx.model;
  std::vector<AnimationChannel> out;
  std::map<std::pair<int, AnimatedProperty>, size_t> animated_by;  // target -> animation
  size_t weight_channels = 0;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& animation = model.animations[a];
    std::string animation_name = quoted_name("animation", a, animation.name);
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      std::string what = animation_name + " channel " + std::to_string(c);
      if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
        ctx.fail(what + " refers to missing sampler " + std::to_string(channel.sampler));
      int node = channel.target_node;
      if (node < 0 || size_t(node) >= model.nodes.size()) ctx.fail(what + " targets missing node " + std::to_string(node));
      if (channel.target_path == "weights") {
        ++weight_channels;
        continue;
      }
      std::optional<AnimatedProperty> property = animated_property(channel.target_path);
      if (!property) ctx.fail(what + " has unknown target path '" + channel.target_path + "'");
      std::string target = quoted_name("node", node, model.nodes[node].name) + " " + channel.target_path;
      if (!model.nodes[node].matrix.empty())
        ctx.fail(what + " targets " + target + ", but the node has a matrix (glTF animates only TRS nodes)");
      auto [it, fresh] = animated_by.try_emplace({node, *property}, a);
      if (!fresh && it->second == a) ctx.fail(what + " targets " + target + ", which another channel of the animation targets");
      if (!fresh) {
        ctx.warnings.add(target + " is animated by " + quoted_name("animation", it->second, model.animations[it->second].name) +
                         " and " + animation_name + ": the later one is played");
        std::erase_if(out, [&](const AnimationChannel& o) { return o.node == node && o.property == *property; });
        it->second = a;
      }
      std::string sampler = what + " sampler " + std::to_string(channel.sampler);
      out.push_back(read_sampler(ctx, accessors, animation.samplers[channel.sampler], *property, sampler));
      out.back().name = what;
      out.back().node = node;
    }
  }
  if (weight_channels > 0)
    ctx.warnings.add("animated morph target weights ignored (" + std::to_string(weight_channels) +
                     " channels): the base shape is rendered");
  return out;
}

std::vector<int> build_rig_nodes(const Context& ctx, const std::vector<Instance>& instances,
                                 std::vector<AnimationChannel> channels, AnimationRig& rig) {
  std::set<int> targets;
  for (const AnimationChannel& c : channels) targets.insert(c.node);
  std::vector<int> rig_node(instances.size(), -1);
  for (size_t i = 0; i < instances.size(); ++i) {  // parents come first
    const Instance& inst = instances[i];
    int moving_parent = inst.parent >= 0 ? rig_node[inst.parent] : -1;
    if (moving_parent < 0 && !targets.count(inst.node)) continue;
    RigNode n = rest_node(ctx, inst.node);
    n.parent = moving_parent;
    if (inst.parent >= 0 && moving_parent < 0) n.parent_world = instances[inst.parent].world;
    rig_node[i] = int(rig.nodes.size());
    rig.nodes.push_back(std::move(n));
    for (const AnimationChannel& c : channels)
      if (c.node == inst.node) {
        rig.channels.push_back(c);
        rig.channels.back().node = rig_node[i];
      }
  }
  return rig_node;
}

void attach_animation(AnimationRig&& rig, Scene& scene) {
  if (rig.channels.empty()) return;
  rig.vertex_count = scene.positions.size();
  std::vector<char> moves(scene.positions.size(), 0);
  for (const AnimatedMesh& m : rig.meshes) std::fill_n(moves.begin() + m.first_vertex, m.positions.size(), 1);
  for (size_t v = 0; v < moves.size(); ++v)
    if (!moves[v]) rig.static_bounds.extend(scene.positions[v]);
  scene.animation = std::make_shared<const SceneAnimation>(std::move(rig));
}

}  // namespace sst::gltf
