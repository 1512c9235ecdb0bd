#include "core/scene/gltf_nodes.h"

#include <string>

namespace sst::gltf {
namespace {

std::vector<int> root_nodes(const Context& ctx) {
  const tinygltf::Model& model = ctx.model;
  if (!model.scenes.empty()) {
    int s = model.defaultScene;
    if (s >= int(model.scenes.size())) ctx.fail("default scene " + std::to_string(s) + " does not exist");
    if (s < 0) s = 0;
    return model.scenes[s].nodes;
  }
  std::vector<char> is_child(model.nodes.size(), 0);
  for (const tinygltf::Node& n : model.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < model.nodes.size()) is_child[c] = 1;
  std::vector<int> roots;
  for (size_t i = 0; i < model.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(int(i));
  return roots;
}

}  // namespace

RigNode rest_node(const Context& ctx, int index) {
  const tinygltf::Node& n = ctx.model.nodes[index];
  std::string what = quoted_name("node", index, n.name);
  RigNode out;
  out.name = n.name;
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) ctx.fail(what + " has a matrix of " + std::to_string(n.matrix.size()) + " numbers (needs 16)");
    if (!all_finite(n.matrix)) ctx.fail(what + " has a non-finite matrix");
    glm::dmat4 M(1.0);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) M[c][r] = n.matrix[c * 4 + r];  // column-major, as glTF
    out.matrix = M;
    return out;
  }
  auto check = [&](const std::vector<double>& v, size_t size, const char* field) {
    if (!v.empty() && v.size() != size) ctx.fail(what + " has a " + field + " of " + std::to_string(v.size()) + " numbers");
    if (!all_finite(v)) ctx.fail(what + " has a non-finite " + field);
  };
  check(n.translation, 3, "translation");
  check(n.rotation, 4, "rotation");
  check(n.scale, 3, "scale");
  if (!n.translation.empty()) out.translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
  if (!n.rotation.empty()) out.rotation = glm::dvec4(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]);
  if (!n.scale.empty()) out.scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
  if (!(glm::dot(out.rotation, out.rotation) > 0.0)) ctx.fail(what + " has a zero rotation quaternion");
  return out;
}

// Each node may have one parent (glTF), which bounds the instance count.
std::vector<Instance> traverse_nodes(const Context& ctx) {
  const tinygltf::Model& model = ctx.model;
  size_t count = model.nodes.size();
  std::vector<int> parents(count, 0);
  for (size_t i = 0; i < count; ++i)
    for (int c : model.nodes[i].children) {
      if (c < 0 || size_t(c) >= count) ctx.fail(quoted_name("node", i, model.nodes[i].name) + " has missing child " + std::to_string(c));
      if (++parents[c] > 1) ctx.fail(quoted_name("node", c, model.nodes[c].name) + " has more than one parent");
    }
  std::vector<Instance> out;
  struct Item { int node; int parent; size_t depth; };
  std::vector<Item> stack;
  std::vector<int> roots = root_nodes(ctx);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
    if (*it < 0 || size_t(*it) >= count) ctx.fail("scene lists missing node " + std::to_string(*it));
    stack.push_back({*it, -1, 0});
  }
  while (!stack.empty()) {
    Item item = stack.back();
    stack.pop_back();
    if (item.depth > count) ctx.fail("node hierarchy has a cycle through node " + std::to_string(item.node));
    glm::dmat4 parent_world = item.parent >= 0 ? out[item.parent].world : glm::dmat4(1.0);
    out.push_back({item.node, item.parent, parent_world * rest_node(ctx, item.node).local_matrix()});
    int self = int(out.size()) - 1;
    const auto& children = model.nodes[item.node].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, self, item.depth + 1});
  }
  return out;
}

}  // namespace sst::gltf
