// VPL sets and tree checks shared by the light-tree tests.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "core/lighttree/light_tree.h"

namespace sst::test {

inline vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (;;) {
    vec3 v(normal(rng), normal(rng), normal(rng));
    float length = glm::length(v);
    if (length > 1e-3f) return v / length;
  }
}

// Positions uniform in a cube of side `scale` at `offset`, random unit normals, RGB intensities
// uniform in [0, 1).
inline VplSet random_vpls(size_t n, uint32_t seed, float scale = 1.0f, vec3 offset = vec3(0.0f)) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  VplSet vpls(n);
  for (Vpl& v : vpls) {
    v.position = offset + scale * vec3(u(rng), u(rng), u(rng));
    v.normal = random_unit(rng);
    v.intensity = vec3(u(rng), u(rng), u(rng));
  }
  return vpls;
}

// VPLs on the six inner faces of a unit room (normals pointing inward): the planar clusters
// the SST substitutes are made for.
inline VplSet room_vpls(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  VplSet vpls(n);
  for (size_t i = 0; i < n; ++i) {
    int face = int(i % 6), axis = face / 2;
    bool high = face % 2 == 1;
    vec3 p(u(rng), u(rng), u(rng));
    p[axis] = high ? 1.0f : 0.0f;
    vec3 normal(0.0f);
    normal[axis] = high ? -1.0f : 1.0f;
    vpls[i] = {p, normal, vec3(u(rng), u(rng), u(rng))};
  }
  return vpls;
}

// Every reachable node of `tree`, root first.
inline std::vector<uint32_t> reachable_nodes(const LightTree& tree) {
  std::vector<uint32_t> order;
  if (tree.empty()) return order;
  std::vector<uint32_t> stack{tree.root};
  while (!stack.empty()) {
    uint32_t i = stack.back();
    stack.pop_back();
    order.push_back(i);
    const LightNode& n = tree[i];
    if (!n.is_leaf()) {
      stack.push_back(n.right);
      stack.push_back(n.left);
    }
  }
  return order;
}

// Leaves below `node`, left to right.
inline std::vector<uint32_t> leaves_below(const LightTree& tree, uint32_t node) {
  std::vector<uint32_t> leaves, stack{node};
  while (!stack.empty()) {
    uint32_t i = stack.back();
    stack.pop_back();
    const LightNode& n = tree[i];
    if (n.is_leaf()) {
      leaves.push_back(i);
    } else {
      stack.push_back(n.right);
      stack.push_back(n.left);
    }
  }
  return leaves;
}

inline bool all_finite(const LightNode& n) {
  bool box_ok = n.empty() || (is_finite(n.bounds_lo) && is_finite(n.bounds_hi));
  return box_ok && is_finite(n.intensity) && is_finite(n.mean) && is_finite(n.normal) && is_finite(n.variance) &&
         std::isfinite(n.similarity) && std::isfinite(n.sigma_z);
}

inline bool same_bytes(const UninitializedVector<LightNode>& a, const UninitializedVector<LightNode>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(LightNode)) == 0);
}

// The same tree: stored nodes byte for byte, the same leaves (their keys) and the same layout.
inline bool same_tree(const LightTree& a, const LightTree& b) {
  return same_bytes(a.nodes, b.nodes) && a.leaf_keys == b.leaf_keys && a.root == b.root &&
         a.first_leaf == b.first_leaf && a.leaf_count == b.leaf_count;
}

}  // namespace sst::test
