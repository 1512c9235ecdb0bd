#include "core/lighttree/light_tree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/lighttree/sort_key.h"
#include "core/lighttree/tree_builders.h"
#include "core/util/error.h"

namespace sst {
namespace {

const std::vector<std::string> kTreeKinds = {"radix", "perfect", "agglomerative"};
const std::vector<std::string> kLengthScales = {"view", "vpl_bounds", "scene_bounds"};
const std::vector<std::string> kLeaves = {"made", "stored"};

// Runs f and adds its wall time to `ms`.
template <class F>
void timed(double& ms, F&& f) {
  auto start = std::chrono::steady_clock::now();
  f();
  ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Every leaf of `tree` into nodes[first_leaf, node_count()), in parallel.
void write_all_leaves(const LightTree& tree, LightNode* nodes) {
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, tree.leaf_count, 4096),
                    [&](const tbb::blocked_range<uint32_t>& r) { write_leaves(tree, nodes, r.begin(), r.end()); });
}

}  // namespace

float tree_length_scale(const LightTreeParams& params, const Bounds3& vpl_bounds, const TreeLengths* lengths) {
  if (params.sigma_max_relative_to == "vpl_bounds") return vpl_bounds.diagonal();
  if (params.sigma_max_relative_to == "view") {
    if (!lengths || !(lengths->view > 0.0f))
      throw Error("light tree: sigma_max_relative_to 'view' needs the view's length, and none was given");
    return lengths->view;
  }
  if (!lengths || lengths->scene_bounds.empty())
    throw Error("light tree: sigma_max_relative_to 'scene_bounds' needs the scene bounds, and none were given");
  return lengths->scene_bounds.diagonal();
}

float node_distance_floor_for(const LightTreeParams& params, const Bounds3& vpl_bounds, float view) {
  if (vpl_bounds.empty()) return 0.0f;
  return vpl_bounds.diagonal() > params.node_distance_floor_above * view ? params.node_distance_floor : 0.0f;
}

void validate(const LightTreeParams& params) {
  if (!contains(kTreeKinds, params.tree))
    throw Error("light tree: unknown tree '" + params.tree + "' (did you mean '" + nearest_name(params.tree, kTreeKinds) +
                "'?)");
  if (!(params.v_min >= 0.0f && params.v_min <= 1.0f))
    throw Error("light tree: v_min " + std::to_string(params.v_min) + " is not in [0, 1]");
  if (!(params.sigma_max >= 0.0f) || !std::isfinite(params.sigma_max))
    throw Error("light tree: sigma_max " + std::to_string(params.sigma_max) + " is not a finite number >= 0");
  if (!contains(kLengthScales, params.sigma_max_relative_to))
    throw Error("light tree: sigma_max_relative_to '" + params.sigma_max_relative_to + "' is not view, vpl_bounds or scene_bounds");
  if (!(params.substitute_max_extent >= 0.0f) || !std::isfinite(params.substitute_max_extent))
    throw Error("light tree: substitute_max_extent " + std::to_string(params.substitute_max_extent) +
                " is not a finite number >= 0");
  if (!(params.node_distance_floor >= 0.0f) || !std::isfinite(params.node_distance_floor))
    throw Error("light tree: node_distance_floor " + std::to_string(params.node_distance_floor) +
                " is not a finite number >= 0");
  if (!(params.node_distance_floor_above >= 0.0f) || !std::isfinite(params.node_distance_floor_above))
    throw Error("light tree: node_distance_floor_above " + std::to_string(params.node_distance_floor_above) +
                " is not a finite number >= 0");
  if (!contains(kLeaves, params.leaves))
    throw Error("light tree: leaves '" + params.leaves + "' is not stored or made");
}

void store_leaves(LightTree& tree) {
  tree.nodes.resize(tree.node_count());  // keeps the internal nodes; adds unwritten elements
  write_all_leaves(tree, tree.nodes.data());
  tree.stored_nodes = tree.node_count();
}

void copy_nodes(const LightTree& tree, std::span<LightNode> out) {
  if (out.size() != tree.node_count())
    throw Error("light tree: copy_nodes into " + std::to_string(out.size()) + " nodes, the tree has " +
                std::to_string(tree.node_count()));
  std::copy(tree.nodes.begin(), tree.nodes.begin() + tree.stored_nodes, out.begin());
  if (tree.stored_nodes < tree.node_count()) write_all_leaves(tree, out.data());
}

void sort_vpls(const VplSet& vpls, const Bounds3& vpl_bounds, LightTreeBuilder::Scratch& scratch, LightTree& tree,
               LightTreeBuildStats& stats) {
  timed(stats.keys_ms, [&] { compute_sort_keys(vpls, vpl_bounds, tree.leaf_keys); });
  // The id bits are already ascending in input order and the sort is stable: sorting only the
  // Morton and normal bits gives the full keys' order, with 5 passes instead of 8. The keys carry
  // their VPL (sort_key_vpl), so no index array travels with them.
  timed(stats.sort_ms, [&] { radix_sort_keys(tree.leaf_keys, scratch.sort, kIdBits, 64); });
}

LightTreeBuilder::LightTreeBuilder() : scratch_(std::make_unique<Scratch>()) {}
LightTreeBuilder::~LightTreeBuilder() = default;
LightTreeBuilder::LightTreeBuilder(LightTreeBuilder&&) noexcept = default;
LightTreeBuilder& LightTreeBuilder::operator=(LightTreeBuilder&&) noexcept = default;

void LightTreeBuilder::build(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths,
                             LightTree& tree, LightTreeBuildStats* stats_out) {
  validate(params);
  // Size limits first, so that a refused build leaves `tree` as it was.
  check_sort_key_capacity(vpls.size());
  if (params.tree == "agglomerative" && vpls.size() > kMaxAgglomerativeVpls)
    throw Error("light tree: tree 'agglomerative' is O(n^2) and limited to " + std::to_string(kMaxAgglomerativeVpls) +
                " VPLs, got " + std::to_string(vpls.size()) + " (use tree 'radix' or 'perfect')");
  LightTreeBuildStats stats;
  auto start = std::chrono::steady_clock::now();
  Bounds3 bounds;
  timed(stats.bounds_ms, [&] { bounds = compute_vpl_bounds(vpls); });
  float scale = tree_length_scale(params, bounds, lengths);
  tree.kind = params.tree;
  tree.vpl_bounds = bounds;
  tree.length_scale = scale;
  tree.v_min = params.v_min;
  tree.sigma_max_abs = params.sigma_max * tree.length_scale;
  SubstituteThresholds thresholds{tree.v_min, tree.sigma_max_abs};
  const bool store = params.leaves == "stored";
  if (params.tree == "agglomerative") {
    timed(stats.hierarchy_ms, [&] { build_agglomerative_tree(vpls, thresholds, tree.length_scale, store, tree); });
  } else {
    sort_vpls(vpls, bounds, *scratch_, tree, stats);
    if (params.tree == "radix") {
      timed(stats.merge_ms, [&] { build_radix_tree(vpls, thresholds, store, *scratch_, tree); });
    } else {
      timed(stats.merge_ms, [&] { build_perfect_tree(vpls, thresholds, store, tree); });
    }
  }
  stats.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (stats_out) *stats_out = stats;
}

LightTree build_light_tree(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths,
                           LightTreeBuildStats* stats) {
  LightTree tree;
  LightTreeBuilder().build(vpls, params, lengths, tree, stats);
  return tree;
}

uint32_t tree_height(const LightTree& tree) {
  if (tree.empty()) return 0;
  uint32_t height = 0;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{tree.root, 0}};
  while (!stack.empty()) {
    auto [node, depth] = stack.back();
    stack.pop_back();
    height = std::max(height, depth);
    if (node >= tree.first_leaf) continue;
    const LightNode& n = tree.nodes[node];
    stack.push_back({n.left, depth + 1});
    stack.push_back({n.right, depth + 1});
  }
  return height;
}

size_t count_suitable_internal(const LightTree& tree) {
  if (tree.empty()) return 0;
  size_t count = 0;
  std::vector<uint32_t> stack{tree.root};
  while (!stack.empty()) {
    const uint32_t node = stack.back();
    stack.pop_back();
    if (node >= tree.first_leaf) continue;
    const LightNode& n = tree.nodes[node];
    if (n.suitable()) ++count;
    stack.push_back(n.left);
    stack.push_back(n.right);
  }
  return count;
}

}  // namespace sst
