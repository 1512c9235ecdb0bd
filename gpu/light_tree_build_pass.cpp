#include "gpu/light_tree_build_pass.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/lighttree/sort_key.h"
#include "core/util/error.h"
#include "gpu/many_light_upload.h"

namespace sst::gpu {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint32_t kGroup = LTB_GROUP_SIZE;
constexpr uint32_t kRadix = LTB_RADIX;
constexpr uint32_t kMaxGroupsX = 65535;  // the smallest maxComputeWorkGroupCount[0] Vulkan allows
constexpr int kDigitBits = 8;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Workgroups for `count` invocations, as (x, y) with x within Vulkan's guaranteed limit.
std::pair<uint32_t, uint32_t> groups_for(uint32_t count) {
  uint32_t groups = std::max<uint32_t>(1, (count + kGroup - 1) / kGroup);
  uint32_t x = std::min(groups, kMaxGroupsX);
  return {x, (groups + x - 1) / x};
}

double run(ComputePipeline& pipeline, const std::vector<const GpuBuffer*>& buffers, const glsl::LightTreeBuildPush& push,
           uint32_t invocations) {
  auto [x, y] = groups_for(invocations);
  return pipeline.dispatch(buffers, &push, x, y);
}

std::unique_ptr<GpuBuffer> buffer(const VulkanContext& context, size_t bytes, const char* what) {
  try {
    return std::make_unique<GpuBuffer>(context, bytes);
  } catch (const std::exception& e) {
    throw Error(std::string("GPU light tree: ") + what + ": " + e.what());
  }
}

}  // namespace

GpuLightTreeBuilder::GpuLightTreeBuilder(const VulkanContext& context) : context_(context) {
  const uint32_t push = sizeof(glsl::LightTreeBuildPush);
  keys_ = std::make_unique<ComputePipeline>(context, "light_tree_keys", 3, push);
  histogram_ = std::make_unique<ComputePipeline>(context, "light_tree_sort_histogram", 2, push);
  scan_ = std::make_unique<ComputePipeline>(context, "light_tree_sort_scan", 2, push);
  scatter_ = std::make_unique<ComputePipeline>(context, "light_tree_sort_scatter", 6, push);
  merge_ = std::make_unique<ComputePipeline>(context, "light_tree_merge", 5, push);
  perfect_leaves_ = std::make_unique<ComputePipeline>(context, "light_tree_perfect_leaves", 3, push);
  perfect_merge_ = std::make_unique<ComputePipeline>(context, "light_tree_perfect_merge", 1, push);
}

GpuLightTreeBuilder::~GpuLightTreeBuilder() = default;

// The sort keys and VPL ids, sorted by key (as the CPU's sort_vpls); `push` holds the grid.
GpuLightTreeBuilder::Sorted GpuLightTreeBuilder::sort(const GpuBuffer& vpls, glsl::LightTreeBuildPush push,
                                                      LightTreeBuildStats& stats) {
  const uint32_t n = push.count, tiles = push.tile_count;
  Sorted out;
  out.keys = buffer(context_, size_t(n) * 8, "sort keys");
  out.ids = buffer(context_, size_t(n) * 4, "VPL ids");
  auto keys_swap = buffer(context_, size_t(n) * 8, "sort keys");
  auto ids_swap = buffer(context_, size_t(n) * 4, "VPL ids");
  auto counts = buffer(context_, size_t(kRadix) * tiles * 4, "radix counts");
  auto totals = buffer(context_, size_t(kRadix) * 4, "radix totals");
  stats.keys_ms = run(*keys_, {&vpls, out.keys.get(), out.ids.get()}, push, n);
  // As the CPU: the id bits are ascending in input order and every pass is stable, so sorting
  // bits [kIdBits, 64) gives the full keys' order.
  for (int shift = kIdBits; shift < 64; shift += kDigitBits) {
    push.shift = uint32_t(shift);
    stats.sort_ms += run(*histogram_, {out.keys.get(), counts.get()}, push, tiles * kGroup);
    stats.sort_ms += scan_->dispatch({counts.get(), totals.get()}, &push, kRadix);
    stats.sort_ms += run(*scatter_,
                         {out.keys.get(), out.ids.get(), counts.get(), totals.get(), keys_swap.get(), ids_swap.get()},
                         push, tiles * kGroup);
    std::swap(out.keys, keys_swap);
    std::swap(out.ids, ids_swap);
  }
  return out;
}

// build_radix_tree's layout: internal nodes [0, n-1), root 0, leaves [n-1, 2n-1) (made, not
// stored: build() stores them on the host where asked to).
void GpuLightTreeBuilder::build_radix(const GpuBuffer& vpls, const Sorted& sorted, glsl::LightTreeBuildPush push,
                                      LightTree& tree, LightTreeBuildStats& stats) {
  const uint32_t n = push.count, node_count = n - 1;
  tree.root = 0;
  tree.first_leaf = n - 1;
  tree.leaf_count = n;
  auto nodes = buffer(context_, size_t(std::max(node_count, 1u)) * sizeof(LightNode), "nodes");
  const size_t meet_bytes = size_t(std::max(n - 1, 1u)) * 4;
  auto meets = buffer(context_, meet_bytes, "meets");
  std::memset(meets->data(), 0, meet_bytes);
  push.first_leaf = n - 1;
  // One invocation per workgroup (see light_tree_merge.comp for why).
  auto [mx, my] = std::pair<uint32_t, uint32_t>{std::min(n, kMaxGroupsX), (n + kMaxGroupsX - 1) / kMaxGroupsX};
  stats.merge_ms =
      merge_->dispatch({&vpls, sorted.ids.get(), sorted.keys.get(), meets.get(), nodes.get()}, &push, mx, my);
  resize_uninitialized(tree.nodes, node_count, /*huge_pages=*/false);
  nodes->download(std::span<LightNode>(tree.nodes));
}

// build_perfect_tree's heap: node 0 unused, root 1, leaves [L, 2L) (as in build_radix). The level above
// the leaves in one pass, then one pass per level, bottom-up (the CPU's subtree blocking only
// orders the same merges).
void GpuLightTreeBuilder::build_perfect(const GpuBuffer& vpls, const Sorted& sorted, glsl::LightTreeBuildPush push,
                                        LightTree& tree, LightTreeBuildStats& stats) {
  const uint32_t leaves = std::bit_ceil(push.count);
  tree.root = 1;
  tree.first_leaf = leaves;
  tree.leaf_count = leaves;
  auto nodes = buffer(context_, size_t(leaves) * sizeof(LightNode), "nodes");
  push.first_leaf = leaves;
  stats.merge_ms = run(*perfect_leaves_, {&vpls, sorted.ids.get(), nodes.get()}, push, std::max(leaves / 2, 1u));
  for (uint32_t level = leaves / 4; level >= 1; level /= 2) {
    push.first_leaf = level;
    push.count = level;
    stats.merge_ms += run(*perfect_merge_, {nodes.get()}, push, level);
  }
  resize_uninitialized(tree.nodes, leaves, /*huge_pages=*/false);
  nodes->download(std::span<LightNode>(tree.nodes));
}

LightTree GpuLightTreeBuilder::build(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths,
                                     LightTreeBuildStats* stats_out, double* gpu_ms) {
  validate(params);
  if (params.tree != "radix" && params.tree != "perfect")
    throw Error("GPU light tree: tree '" + params.tree +
                "' is built on the CPU only (the GPU builds 'radix' and 'perfect')");
  check_sort_key_capacity(vpls.size());
  LightTreeBuildStats stats;
  auto start = Clock::now();
  Bounds3 bounds = compute_vpl_bounds(vpls);
  stats.bounds_ms = ms_since(start);

  const uint32_t n = uint32_t(vpls.size());
  LightTree tree;
  tree.kind = params.tree;
  tree.vpls = vpls;
  tree.vpl_count = n;
  tree.vpl_bounds = bounds;
  tree.length_scale = tree_length_scale(params, bounds, lengths);
  tree.v_min = params.v_min;
  tree.sigma_max_abs = params.sigma_max * tree.length_scale;
  tree.root = kNoNode;  // both builders' empty tree
  tree.first_leaf = tree.leaf_count = 0;
  double gpu_total = 0.0;
  if (n > 0) {
    MortonGrid grid = MortonGrid::over(bounds);
    glsl::LightTreeBuildPush push{};
    push.count = n;
    push.tile_count = (n + kGroup - 1) / kGroup;
    push.grid_origin = grid.origin;
    push.grid_scale = grid.scale;
    push.v_min = tree.v_min;
    push.sigma_max_abs = tree.sigma_max_abs;
    auto gpu_vpls = upload_buffer(context_, pack_vpls(vpls), "GPU light tree: VPLs");
    Sorted sorted = sort(*gpu_vpls, push, stats);
    if (params.tree == "radix")
      build_radix(*gpu_vpls, sorted, push, tree, stats);
    else
      build_perfect(*gpu_vpls, sorted, push, tree, stats);
    tree.leaf_keys.resize(n);  // uvec2 keys: a uint64_t's bytes (light_tree_build_layout.h)
    sorted.keys->download(std::span<uint64_t>(tree.leaf_keys));
    tree.stored_nodes = uint32_t(tree.nodes.size());
    if (params.leaves == "stored") store_leaves(tree);  // on the host, as the CPU's build
    gpu_total = stats.keys_ms + stats.sort_ms + stats.hierarchy_ms + stats.merge_ms;
  }
  stats.total_ms = ms_since(start);
  if (stats_out) *stats_out = stats;
  if (gpu_ms) *gpu_ms = gpu_total;
  return tree;
}

LightTree build_light_tree_gpu(const VulkanContext& context, const VplSet& vpls, const LightTreeParams& params,
                               const TreeLengths* lengths, LightTreeBuildStats* stats, double* gpu_ms) {
  return GpuLightTreeBuilder(context).build(vpls, params, lengths, stats, gpu_ms);
}

}  // namespace sst::gpu
