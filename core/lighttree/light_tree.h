// Light trees over a VPL set (docs/design/methods.md, light trees): a binary hierarchy whose
// every node carries the summed intensity, bounding box and VPL count of its subtree, plus the
// SST substitute distribution of its VPLs (Tatzgern et al. 2020, eqs. 1-3). The tree samplers
// (slc, sst, rtslc, hybrid) walk it; all builders produce the same flat node layout, so every
// sampler works on every tree.
// Its parameters are LightTreeParams below; their visit() help is their documentation.
//
// Length scale D. sigma_max is a fraction of D, never an absolute length, because scenes come
// in millimetres and kilometres. A method's D is the view's (TreeLengths::view, twice the median
// distance from the camera to what it sees), which nothing outside the view changes; a tree built
// without a camera takes the diagonal of the bounding box of the VPL positions, which a sunlit
// ground around a room inflates (docs/design/lengths.md). The paper's sigma_max = 0.1 is in its scene
// units: roughly metres, in rooms some 20 units across, so 0.1 / 20 = 0.005 of D (measured
// against the box diagonal of such a room, ~30 units, it would be nearer 0.003: the conversion
// is a rough one either way, so the sensitivity to sigma_max is worth measuring). The
// thesis's 0.3, by the same yardstick (it does not state its scene scale), is 0.015 of D.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/lighttree/light_node.h"
#include "core/lighttree/sort_key.h"
#include "core/math/math.h"
#include "core/util/memory.h"
#include "core/util/params.h"
#include "core/vpl/vpl.h"

namespace sst {

// Node index layout, by builder (`root`, `first_leaf` and `leaf_count` say it for any tree):
// - radix, agglomerative: internal nodes [0, n-1), root 0; leaves [n-1, 2n-1). A single VPL
//   is a tree of one leaf, node 0. Radix leaves are in sort-key order; agglomerative leaf
//   n-1+i holds VPL i.
// - perfect: heap. Node 0 is unused (an empty padding leaf), root 1, children of i are 2i and
//   2i+1, leaves [L, 2L) with L = the power of two >= n: VPLs in sort-key order, then padding
//   leaves (zero intensity, empty box, VPL index kNoNode). The nodes of level l are
//   [2^l, 2^(l+1)).
//
// A leaf holds nothing its VPL does not (make_leaf, substitute.h). With LightTreeParams::leaves =
// made only the nodes below first_leaf are stored, and node() makes a leaf from its VPL when it
// is read: 96 bytes a VPL instead of 192, for walks that gather the leaves' VPLs from wherever
// they lie (docs/performance.md has the measured cost).
struct LightTree {
  std::string kind;  // the builder: radix, perfect, agglomerative
  // [0, stored_nodes): every node, or only those below first_leaf (leaves = made). Builders:
  // resize_uninitialized, then write every node.
  UninitializedVector<LightNode> nodes;
  uint32_t stored_nodes = 0;  // nodes.size()
  // Leaf i's sort key, for i < vpl_count (radix, perfect: ascending; agglomerative: i);
  // sort_key_vpl(leaf_keys[i]) is its VPL. Leaves past vpl_count are perfect trees' padding.
  std::vector<uint64_t> leaf_keys;
  // The VPLs it was built over; they must outlive every use of the tree, whose leaves they are.
  std::span<const Vpl> vpls;
  uint32_t root = kNoNode;  // kNoNode for an empty VPL set
  uint32_t first_leaf = 0;
  uint32_t leaf_count = 0;  // including padding leaves
  uint32_t vpl_count = 0;
  Bounds3 vpl_bounds;
  float length_scale = 0.0f;  // D (see the top of this file)
  float v_min = 0.0f;         // the thresholds the kSuitable flags were computed with
  float sigma_max_abs = 0.0f; // sigma_max * D, in scene units

  bool empty() const { return root == kNoNode; }
  // Stored and made nodes together: first_leaf + leaf_count.
  uint32_t node_count() const { return empty() ? 0 : first_leaf + leaf_count; }
  // Node i < node_count(), stored or made from its VPL (light_tree_node.h).
  LightNode node(uint32_t i) const;
  // Leaf first_leaf + position: its VPL's, or a padding leaf past the VPLs.
  LightNode leaf(uint32_t position) const;
  LightNode operator[](uint32_t i) const { return node(i); }
};

}  // namespace sst

#define LIGHT_TREE_PARAM const ::sst::LightTree &tree,
#define LIGHT_TREE_ARG tree,
#define LIGHT_TREE_STORED(i) tree.nodes[i]
#define LIGHT_TREE_LEAF_VPL(j) ::sst::sort_key_vpl(tree.leaf_keys[j])
#define LIGHT_TREE_VPL(v) tree.vpls[v]
#include "core/lighttree/light_tree_node.h"

namespace sst {

inline LightNode LightTree::node(uint32_t i) const {
  return light_tree_node(*this, i, stored_nodes, first_leaf, vpl_count, {v_min, sigma_max_abs});
}
inline LightNode LightTree::leaf(uint32_t position) const {
  return light_tree_leaf(*this, position, vpl_count, {v_min, sigma_max_abs});
}

// The lengths D may be relative to besides the VPLs' own bounds (LightTreeParams::sigma_max_relative_to).
struct TreeLengths {
  Bounds3 scene_bounds;
  float view = 0.0f;  // D of sigma_max_relative_to = view (TreeSamplerBase: 2 x median_view_distance)
};

struct LightTreeParams {
  std::string tree = "radix";
  float v_min = 0.5f;
  float sigma_max = 0.005f;
  std::string sigma_max_relative_to = "vpl_bounds";  // the methods' default is view (TreeMethodParams)
  std::string leaves = "made";
  float substitute_max_extent = 1.0f;
  float node_distance_floor = 0.1f;
  float node_distance_floor_above = 50.0f;  // the methods' defaults: TreeMethodParams

  template <class V>
  void visit(V&& v) {
    v("tree", tree,
      "light tree builder: radix (Karras 2012, the SST paper's), perfect (heap layout, the only one rtslc and hybrid "
      "accept) or agglomerative (Walter 2005; O(n^2), at most 20000 VPLs)");
    v("v_min", v_min,
      "substitutes (sst, hybrid): a node is suitable only if the normal similarity v of its VPLs is >= v_min, in "
      "[0, 1] (SST paper 0.5, hybrid thesis 0.7)");
    v("sigma_max", sigma_max,
      "substitutes (sst, hybrid): a node is suitable only if also its VPLs' standard deviation along its normal is "
      "<= sigma_max x D (SST paper 0.1 scene units ~ 0.005 D, hybrid thesis 0.3 ~ 0.015 D)");
    v("sigma_max_relative_to", sigma_max_relative_to,
      "the length D of sigma_max (and of sst's distance_floor): view (twice the median distance from the camera to "
      "what it sees: nothing outside the view changes it), vpl_bounds (the diagonal of the VPLs' bounding box, "
      "which a sunlit ground plane around a room inflates) or scene_bounds (the scene's)");
    v("substitute_max_extent", substitute_max_extent,
      "substitutes (sst, hybrid): a suitable node stands in for its VPLs only where its box's diagonal is at most "
      "this times its distance from the shading point (0: wherever it is suitable, the papers' rule; they bound no "
      "node's width, and a wide coplanar ground biased sst by -14% at 10 km)");
    v("node_distance_floor", node_distance_floor,
      "where the VPLs span more than node_distance_floor_above view lengths: the walks' distance to a node's box "
      "is at least this times the box's diagonal (slc, sst, rtslc, hybrid; box_distance2_floored), since under "
      "the papers' rules a box kilometres wide that holds the shading point outweighs a bright room beside it by "
      "its power alone; 0 keeps the papers' rules everywhere (slc ignores distance within one diagonal of a box, "
      "sst floors it at distance_floor x D, the hybrid at the VPL clamp, rtslc not at all)");
    v("node_distance_floor_above", node_distance_floor_above,
      "the floor acts only when the diagonal of the VPLs' bounding box exceeds this many view lengths (twice the "
      "median distance from the camera to what it sees; the tree's counter vpl_view_lengths); 0: always. slc 2.5: "
      "the floor lowered its error at every extent measured from 2.6 view lengths on and raised it at 2.1, 2.49 and "
      "in the breakfast room (0.7); sst 2: it lowered sst's from 2.1 on; rtslc and hybrid 50: it raised their "
      "error at 7.3 and 14.5 and lowered it at 145 and 1445 (results/README.md, 'Large extents')");
    v("leaves", leaves,
      "made (only the internal nodes stored; a walk makes a leaf from its VPL when it reaches it: 96 bytes a VPL "
      "less and a single frame's build 2-7x faster, at the same sampling time) or stored (every node in the tree's "
      "array: a walk reads a leaf beside its sibling instead of gathering its VPL); the same images");
  }
};

// Throws sst::Error naming the first bad parameter.
void validate(const LightTreeParams& params);

// D for `params` over VPLs bounded by `vpl_bounds`. Throws sst::Error when `lengths` lacks what
// sigma_max_relative_to asks for.
float tree_length_scale(const LightTreeParams& params, const Bounds3& vpl_bounds, const TreeLengths* lengths);

// The node-distance floor the walks use (SamplerParams::node_distance_floor): params'
// node_distance_floor where the VPLs' bounding box is wider than node_distance_floor_above view
// lengths `view` (an empty set: never), else 0.
float node_distance_floor_for(const LightTreeParams& params, const Bounds3& vpl_bounds, float view);

// Wall time of each build stage, in milliseconds.
struct LightTreeBuildStats {
  double bounds_ms = 0.0;     // VPL bounds and input checks
  double keys_ms = 0.0;       // sort keys
  double sort_ms = 0.0;       // radix sort
  double hierarchy_ms = 0.0;  // the agglomerative pairing (0 for radix and perfect trees, whose merge
                              // finds or needs no topology)
  double merge_ms = 0.0;      // bottom-up leaves, intensities, boxes and SST substitutes
  double total_ms = 0.0;
};

// Scratch buffers of a build, kept between builds (one per frame) so that a rebuild of the same
// size allocates nothing. Use one builder per thread.
class LightTreeBuilder {
 public:
  LightTreeBuilder();
  ~LightTreeBuilder();
  LightTreeBuilder(LightTreeBuilder&&) noexcept;
  LightTreeBuilder& operator=(LightTreeBuilder&&) noexcept;

  // Builds into `tree`, reusing its node storage. `lengths` is needed only with
  // sigma_max_relative_to = view or scene_bounds. Throws sst::Error on bad parameters, too many VPLs
  // or a bad VPL, before `tree` is touched.
  void build(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths, LightTree& tree,
             LightTreeBuildStats* stats = nullptr);
  // The tree's leaves are the VPLs (LightTree::vpls): a temporary set would leave it dangling.
  void build(VplSet&&, const LightTreeParams&, const Bounds3*, LightTree&, LightTreeBuildStats* = nullptr) = delete;

  struct Scratch;

 private:
  std::unique_ptr<Scratch> scratch_;
};

// Writes the leaves into tree.nodes (LightTreeParams::leaves = stored), made as node() makes them.
void store_leaves(LightTree& tree);

// Every node of `tree`, stored or made, into `out` (node_count() elements), for a reader of whole
// nodes (the GPU sampler's buffer) that should not hold a second copy of the tree.
void copy_nodes(const LightTree& tree, std::span<LightNode> out);

// The one factory: a tree over `vpls` by params.tree.
LightTree build_light_tree(const VplSet& vpls, const LightTreeParams& params, const TreeLengths* lengths = nullptr,
                           LightTreeBuildStats* stats = nullptr);
LightTree build_light_tree(VplSet&&, const LightTreeParams&, const TreeLengths* = nullptr,
                           LightTreeBuildStats* = nullptr) = delete;  // see LightTreeBuilder::build

// Longest root-to-leaf path in edges (0 for a single leaf); for reports and tests.
uint32_t tree_height(const LightTree& tree);
// Number of internal nodes flagged suitable.
size_t count_suitable_internal(const LightTree& tree);

}  // namespace sst
