// Building the emitter tree that the `tree` and `slc` light samplers walk
// (core/lights/emitter_tree.h; layout EmitterNode, core/lights/light_layout.h). Two builds, one
// layout: node 0 unused, the root at 1, an inner node's two children side by side at `children`
// and `children + 1`, every node's `parent`, then one node per directional light. Every inner
// node merges its children: boxes united, intensities summed, normal cones united (pbrt-v4's
// DirectionCone::Union, in double, widened by kConeSlack so float storage stays conservative),
// theta_e the larger of the two, two-sidedness if either is.
// - saoh (the default): top down, each range of lights split where the surface area
//   orientation heuristic of Conty Estevez & Kulla 2018 ("Importance Sampling of Many Lights
//   with Adaptive Tree Splitting", as pbrt-v4's BVHLightSampler builds it) is least: per axis,
//   12 buckets of the lights' centres; a side costs its power x M_omega (the solid-angle measure
//   of its normal and emission cones) x its box's surface area, times the node's largest extent
//   over its extent along the axis (Kr). So lights that differ in power or facing end in
//   different subtrees even where they sit side by side. One light per leaf; 2n - 1 nodes for
//   n lights, in depth-first order of sibling pairs; a depth of at most kEmitterTreeMaxDepth.
// - morton: the lights ordered by the Morton code of their box centres on a 1024^3 grid over the
//   centres' bounds (ties by entry), laid out as the leaves of a perfect binary tree in heap
//   order (children of i at 2i, 2i + 1; leaves padded to a power of two with intensity-0 nodes)
//   and merged bottom up: Yuksel's (SLC) and RTSLC's layout, O(n log n), blind to power and
//   orientation.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/lights/light_layout.h"
#include "core/util/memory.h"

namespace sst {

// Extra half angle (radians) of every merged cone, over the rounding of its float axis and cosine.
inline constexpr double kConeSlack = 1e-6;

// The deepest a leaf may lie below the root: the pmf reads a leaf's path as a 64-bit trail.
inline constexpr uint32_t kEmitterTreeMaxDepth = 64;

// How the tree is built (RenderOptions::light_tree).
enum class EmitterTreeBuild : uint32_t { Saoh, Morton };
// "saoh, morton", for help and errors.
const char* emitter_tree_build_names();
const char* emitter_tree_build_name(EmitterTreeBuild build);
// Throws sst::Error naming the valid values for an unknown name.
EmitterTreeBuild parse_emitter_tree_build(const std::string& name);

// The distance in the tree samplers' importance (RenderOptions::light_tree_distance;
// EMITTER_DISTANCE_*, core/lights/emitter_tree.h says what each is).
enum class EmitterDistance : uint32_t {
  Centre = EMITTER_DISTANCE_CENTRE,
  Box = EMITTER_DISTANCE_BOX,
  Mixed = EMITTER_DISTANCE_MIXED,
};
// "centre, box, mixed", for help and errors.
const char* emitter_distance_names();
const char* emitter_distance_name(EmitterDistance distance);
// Throws sst::Error naming the valid values for an unknown name.
EmitterDistance parse_emitter_distance(const std::string& name);

// The tree's nodes: written once by the build, in parallel, without a serial fill before.
using EmitterNodes = UninitializedVector<glsl::EmitterNode>;

struct EmitterTree {
  // 2 leaves + directional lights: node 0 unused, 1 .. 2 leaves - 1 the tree, then one node per
  // directional light (what light_tree[] holds on the GPU).
  EmitterNodes nodes;
  uint32_t leaves = 0;             // leaves (morton: padded to a power of two); 0 when no light is in the tree
  uint32_t directional_count = 0;
  std::vector<uint32_t> node_of_entry;  // per distribution entry: its node, or LIGHT_NONE
};

// The tree over `lights`, one leaf-form node per distribution entry: `entry` set to its index,
// flags EMITTER_DIRECTIONAL for a directional light (kept beside the tree), box, cone and
// intensity filled in. A light of intensity 0 (or not finite) gets no node. Parallel (oneTBB);
// the same tree for any number of threads.
EmitterTree build_emitter_tree(std::span<const glsl::EmitterNode> lights,
                               EmitterTreeBuild build = EmitterTreeBuild::Saoh);

// A cut of the tree (`nodes`: light_tree[] with `leaves` leaves and `directional_count`
// directional lights after them): nodes whose subtrees are disjoint and hold every light of
// non-zero intensity, for RTSLC's per-block cuts on real lights (core/manylight/rtslc/
// rtslc_direct.h). Greedy, as RTSLC's cuts over VPLs: start from the root and the directional
// lights, then repeatedly replace the inner node of largest importance seen from the point
// (emitter_importance at p with shading normal n and distance rule `distance`; ties, and every
// node when `seen` is false, by intensity) by its children of non-zero intensity, until the cut
// has `max_nodes` nodes or only leaves. The start may exceed max_nodes (every directional light
// is in every cut). Appends to `cut`.
void emitter_tree_cut(std::span<const glsl::EmitterNode> nodes, uint32_t leaves, uint32_t directional_count,
                      uint32_t distance, bool seen, glm::vec3 p, glm::vec3 n, uint32_t max_nodes,
                      std::vector<uint32_t>& cut);

// Merges two nodes as an inner node of the tree (exposed for tests); `children` and `parent`
// are left for the caller.
glsl::EmitterNode merge_emitter_nodes(const glsl::EmitterNode& a, const glsl::EmitterNode& b);

// The solid-angle measure M_omega of Conty Estevez & Kulla 2018 (eq. 1) for a normal cone of half
// angle theta_o and emission spread theta_e (radians): the integral of the emission's angular
// falloff bound over the sphere; pi for a one-sided flat emitter, 4 pi for a point light.
double emitter_cone_measure(double theta_o, double theta_e);

}  // namespace sst
