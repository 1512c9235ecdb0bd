// Building the emitter tree that the `tree` and `slc` light samplers walk
// (core/lights/emitter_tree.h; layout EmitterNode, core/lights/light_layout.h). The lights are
// ordered by the Morton code of their box centres on a 1024^3 grid over the centres' bounds
// (ties by entry), laid out as the leaves of a perfect binary tree in heap order (root 1,
// children 2i and 2i + 1, leaves padded to a power of two with intensity-0 nodes), and merged
// bottom up: boxes united, intensities summed, normal cones united (pbrt-v4's
// DirectionCone::Union, in double, widened by kConeSlack so float storage stays conservative),
// theta_e the larger of the two, two-sidedness if either is. A perfect tree over Morton order is
// Yuksel's (SLC) and RTSLC's layout: O(n log n), a depth of ceil(log2 n), and a light's path is
// the bits of its leaf index, so no tree needs pointers.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/lights/light_layout.h"
#include "core/util/memory.h"

namespace sst {

// Extra half angle (radians) of every merged cone, over the rounding of its float axis and cosine.
inline constexpr double kConeSlack = 1e-6;

// The tree's nodes: written once by the build, in parallel, without a serial fill before.
using EmitterNodes = UninitializedVector<glsl::EmitterNode>;

struct EmitterTree {
  // 2 leaves + directional lights: node 0 unused, 1 .. 2 leaves - 1 the heap, then one node per
  // directional light (what light_tree[] holds on the GPU).
  EmitterNodes nodes;
  uint32_t leaves = 0;             // leaf slots, a power of two; 0 when no light is in the tree
  uint32_t directional_count = 0;
  std::vector<uint32_t> node_of_entry;  // per distribution entry: its node, or LIGHT_NONE
};

// The tree over `lights`, one leaf-form node per distribution entry: `entry` set to its index,
// flags EMITTER_DIRECTIONAL for a directional light (kept beside the tree), box, cone and
// intensity filled in. A light of intensity 0 (or not finite) gets no node. Parallel (oneTBB).
EmitterTree build_emitter_tree(std::span<const glsl::EmitterNode> lights);

// A cut of the tree (`nodes`: light_tree[] with `leaves` leaf slots and `directional_count`
// directional lights after them): nodes whose subtrees are disjoint and hold every light of
// non-zero intensity, for RTSLC's per-block cuts on real lights (core/manylight/rtslc/
// rtslc_direct.h). Greedy, as RTSLC's cuts over VPLs: start from the root and the directional
// lights, then repeatedly replace the inner node of largest importance seen from the point
// (emitter_importance at p with shading normal n; ties, and every node when `seen` is false,
// by intensity) by its children of non-zero intensity, until the cut has `max_nodes` nodes or
// only leaves. The start may exceed max_nodes (every directional light is in every cut).
// Appends to `cut`.
void emitter_tree_cut(std::span<const glsl::EmitterNode> nodes, uint32_t leaves, uint32_t directional_count,
                      bool seen, glm::vec3 p, glm::vec3 n, uint32_t max_nodes, std::vector<uint32_t>& cut);

// Merges two nodes as an inner node of the tree (exposed for tests).
glsl::EmitterNode merge_emitter_nodes(const glsl::EmitterNode& a, const glsl::EmitterNode& b);

}  // namespace sst
