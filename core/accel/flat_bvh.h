// The BVH of the Vulkan backend: built on the CPU with Embree's rtcBuildBVH (SAH,
// RTC_BUILD_QUALITY_HIGH, binary, leaves of at most 4 triangles), flattened depth first into the
// node and triangle arrays of core/accel/bvh_layout.h, ready for upload. flat_bvh_intersect and
// flat_bvh_occluded run the shared traversal (core/accel/bvh_traverse.h) on the CPU, the very
// code the shaders run, so the tree and the traversal are tested against Embree here.
#pragma once
#include <cstdint>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/math/math.h"
#include "core/scene/scene.h"
#include "core/accel/bvh_layout.h"

namespace sst {

struct FlatBvhOptions {
  // Spatial splits (Embree's SBVH builder, with triangle clipping): a triangle may be referenced
  // by several leaves, each with the bounds of its clipped part. Fewer, tighter boxes for long
  // thin triangles at the price of a longer build and duplicated triangle records.
  bool spatial_splits = true;
  uint32_t max_leaf_size = 4;  // triangles per leaf; larger leaves are tried if the depth limit hits
};

struct FlatBvhStats {
  uint32_t node_count = 0;
  uint32_t leaf_count = 0;
  uint32_t max_depth = 0;        // of a leaf, the root at 0; <= BVH_STACK_SIZE
  uint32_t triangle_refs = 0;    // triangles[] size: scene triangles + spatial-split copies
  uint32_t max_leaf_size = 0;    // largest leaf, in triangles
  uint32_t skipped_triangles = 0;  // with non-finite vertices, left out of the tree
  uint32_t alpha_tested_refs = 0;  // triangles[] flagged BVH_TRIANGLE_ALPHA_TESTED
  double build_ms = 0.0;         // Embree build + flattening
};

struct FlatBvh {
  std::vector<glsl::BvhNode> nodes;          // nodes[0] is the root
  std::vector<glsl::BvhTriangle> triangles;  // in leaf order
  FlatBvhStats stats;
};

// Throws sst::Error when Embree fails or no tree within the traversal's stack depth exists.
FlatBvh build_flat_bvh(const Scene& scene, const FlatBvhOptions& options = {});

// Same fields and conventions as EmbreeAccel's Hit (t = inf and triangle = UINT32_MAX on a miss,
// Embree's barycentrics), so the CPU shading code consumes either.
using FlatHit = Hit;

// Closest hit with tmin <= t < tmax, by the shared traversal. `scene`, the one the tree was built
// from, answers the alpha tests (triangle_alpha_passes); a tree with alpha-tested triangles
// (stats.alpha_tested_refs > 0) needs it, else sst::Error.
FlatHit flat_bvh_intersect(const FlatBvh& bvh, vec3 origin, vec3 dir, float tmin, float tmax,
                           const Scene* scene = nullptr);
// Any hit with tmin <= t < tmax.
bool flat_bvh_occluded(const FlatBvh& bvh, vec3 origin, vec3 dir, float tmin, float tmax, const Scene* scene = nullptr);

}  // namespace sst
