// The shared traversal's watertightness needs unfused multiply-adds (see bvh_traverse.h): keep
// the compiler from contracting a * b - c * d into an FMA in this file, whatever the -march.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "core/accel/flat_bvh.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <new>
#include <string>

#include "core/scene/scene_access.h"
#include "core/scene/triangle_attributes.h"
#include "core/util/error.h"

namespace sst {
namespace {
// What the shared traversal reads: the tree, and the scene for the alpha tests.
struct FlatBvhQuery {
  const FlatBvh& bvh;
  const Scene* scene;
};
}  // namespace
}  // namespace sst

// The shared traversal, compiled as C++ over a FlatBvh (in namespace sst::glsl).
#define BVH_CONTEXT_PARAM const sst::FlatBvhQuery &bvh_query,
#define BVH_CONTEXT_ARG bvh_query,
#define BVH_NODE(i) bvh_query.bvh.nodes[i]
#define BVH_TRIANGLE(i) bvh_query.bvh.triangles[i]
#define BVH_ALPHA_TEST(triangle, b) ::sst::triangle_alpha_passes(*bvh_query.scene, triangle, b)
#include "core/accel/bvh_traverse.h"

namespace sst {
namespace {

// Build-time tree in Embree's thread-local arena (freed with the RTCBVH).
struct BuildNode {
  bool leaf;
};
struct BuildInner : BuildNode {
  RTCBounds bounds[2];
  BuildNode* children[2];
};
struct BuildLeaf : BuildNode {
  uint32_t count;
  uint32_t triangles[1];  // count entries follow (allocated with the node)
};

struct BuildInput {
  const Scene* scene;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16);
  auto* node = new (mem) BuildInner;
  node->leaf = false;
  node->children[0] = node->children[1] = nullptr;
  return node;
}

void set_children(void* node_ptr, void** children, unsigned int child_count, void*) {
  auto* node = static_cast<BuildInner*>(node_ptr);
  for (unsigned i = 0; i < child_count && i < 2; ++i) node->children[i] = static_cast<BuildNode*>(children[i]);
}

void set_bounds(void* node_ptr, const RTCBounds** bounds, unsigned int child_count, void*) {
  auto* node = static_cast<BuildInner*>(node_ptr);
  for (unsigned i = 0; i < child_count && i < 2; ++i) node->bounds[i] = *bounds[i];
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(BuildLeaf) + count * sizeof(uint32_t), 16);
  auto* leaf = new (mem) BuildLeaf;
  leaf->leaf = true;
  leaf->count = uint32_t(count);
  for (size_t i = 0; i < count; ++i) leaf->triangles[i] = prims[i].primID;
  return leaf;
}

// Bounds of the parts of a triangle (already clipped to prim's box) on either side of the plane
// x[dim] = pos. Crossing points are padded by a few ulps before the intersection with the box,
// so that rounding in the interpolation cannot make a clipped box miss part of its triangle.
void split_triangle(const RTCBuildPrimitive* prim, unsigned int dim, float pos, RTCBounds* left_out,
                    RTCBounds* right_out, void* user) {
  const Scene& scene = *static_cast<const BuildInput*>(user)->scene;
  const uvec3 tri = scene.triangles[prim->primID];
  const vec3 v[3] = {scene.positions[tri.x], scene.positions[tri.y], scene.positions[tri.z]};
  Bounds3 left, right;
  for (int i = 0; i < 3; ++i) {
    vec3 a = v[i], b = v[(i + 1) % 3];
    float ad = a[int(dim)], bd = b[int(dim)];
    if (ad <= pos) left.extend(a);
    if (ad >= pos) right.extend(a);
    if ((ad < pos && bd > pos) || (ad > pos && bd < pos)) {
      vec3 p = glm::mix(a, b, (pos - ad) / (bd - ad));
      p[int(dim)] = pos;
      vec3 pad = 4e-7f * (glm::abs(a) + glm::abs(b));
      pad[int(dim)] = 0.0f;
      for (Bounds3* side : {&left, &right}) {
        side->extend(p - pad);
        side->extend(p + pad);
      }
    }
  }
  const vec3 lo(prim->lower_x, prim->lower_y, prim->lower_z), hi(prim->upper_x, prim->upper_y, prim->upper_z);
  auto write = [&](Bounds3 b, RTCBounds* out) {
    b.lo = glm::max(b.lo, lo);
    b.hi = glm::min(b.hi, hi);
    out->lower_x = b.lo.x, out->lower_y = b.lo.y, out->lower_z = b.lo.z;
    out->upper_x = b.hi.x, out->upper_y = b.hi.y, out->upper_z = b.hi.z;
    out->align0 = out->align1 = 0.0f;
  };
  left.hi[int(dim)] = std::min(left.hi[int(dim)], pos);
  right.lo[int(dim)] = std::max(right.lo[int(dim)], pos);
  write(left, left_out);
  write(right, right_out);
}

Bounds3 to_bounds(const RTCBounds& b) {
  Bounds3 r;
  r.lo = vec3(b.lower_x, b.lower_y, b.lower_z);
  r.hi = vec3(b.upper_x, b.upper_y, b.upper_z);
  return r;
}

struct Flattener {
  const Scene& scene;
  FlatBvh& out;

  uint32_t emit(const BuildNode* node, const Bounds3& bounds, uint32_t depth) {
    const uint32_t index = uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    out.nodes[index].bounds_min = bounds.lo;
    out.nodes[index].bounds_max = bounds.hi;
    out.stats.max_depth = std::max(out.stats.max_depth, depth);
    if (node->leaf) {
      auto* leaf = static_cast<const BuildLeaf*>(node);
      out.nodes[index].first_or_right = uint32_t(out.triangles.size());
      out.nodes[index].count_and_flags = BVH_LEAF_FLAG | leaf->count;
      for (uint32_t i = 0; i < leaf->count; ++i) {
        const uint32_t t = leaf->triangles[i];
        const uvec3 tri = scene.triangles[t];
        glsl::BvhTriangle& record = out.triangles.emplace_back();
        record.v0 = scene.positions[tri.x];
        record.v1 = scene.positions[tri.y];
        record.v2 = scene.positions[tri.z];
        record.triangle = t;
        record.flags = triangle_alpha_tested(scene, t) ? BVH_TRIANGLE_ALPHA_TESTED : 0u;
        record.reserved = 0;
        if (record.flags != 0u) ++out.stats.alpha_tested_refs;
      }
      ++out.stats.leaf_count;
      out.stats.max_leaf_size = std::max(out.stats.max_leaf_size, leaf->count);
      return index;
    }
    auto* inner = static_cast<const BuildInner*>(node);
    const Bounds3 left = to_bounds(inner->bounds[0]), right = to_bounds(inner->bounds[1]);
    // The axis along which the children lie apart: traversal takes the near one first.
    const vec3 gap = glm::abs(right.center() - left.center());
    const uint32_t axis = gap.x >= gap.y && gap.x >= gap.z ? 0u : (gap.y >= gap.z ? 1u : 2u);
    const vec3 d = right.center() - left.center();
    // Keep "left child = low side of the axis" so that the sign of the ray picks the near child.
    const bool swap = d[int(axis)] < 0.0f;
    const int first = swap ? 1 : 0;
    emit(inner->children[first], first == 0 ? left : right, depth + 1);
    const uint32_t right_index = emit(inner->children[1 - first], first == 0 ? right : left, depth + 1);
    out.nodes[index].first_or_right = right_index;
    out.nodes[index].count_and_flags = axis;
    return index;
  }
};

}  // namespace

FlatBvh build_flat_bvh(const Scene& scene, const FlatBvhOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  FlatBvh out;

  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(options.spatial_splits ? 2 * scene.triangles.size() : scene.triangles.size());
  Bounds3 root_bounds;
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const uvec3 tri = scene.triangles[i];
    const vec3 p0 = scene.positions[tri.x], p1 = scene.positions[tri.y], p2 = scene.positions[tri.z];
    if (!is_finite(p0) || !is_finite(p1) || !is_finite(p2)) {  // Bounds3::extend would drop a NaN
      ++out.stats.skipped_triangles;
      continue;
    }
    Bounds3 b;
    b.extend(p0);
    b.extend(p1);
    b.extend(p2);
    root_bounds.extend(b);
    RTCBuildPrimitive p;
    p.lower_x = b.lo.x, p.lower_y = b.lo.y, p.lower_z = b.lo.z;
    p.upper_x = b.hi.x, p.upper_y = b.hi.y, p.upper_z = b.hi.z;
    p.geomID = 0;
    p.primID = uint32_t(i);
    prims.push_back(p);
  }
  const size_t prim_count = prims.size();

  if (prim_count == 0) {  // an empty leaf as the root: every ray misses
    glsl::BvhNode& root = out.nodes.emplace_back();
    root.bounds_min = root.bounds_max = vec3(0.0f);
    root.first_or_right = 0;
    root.count_and_flags = BVH_LEAF_FLAG;
    out.stats.node_count = out.stats.leaf_count = 1;
  } else {
    RTCDevice device = rtcNewDevice("");
    if (!device) throw Error("could not create an Embree device");
    BuildInput input{&scene};
    std::vector<RTCBuildPrimitive> work;
    void* root = nullptr;
    RTCBVH bvh = nullptr;
    // Embree turns a subtree that would exceed maxDepth into one large leaf; should even that
    // fail (pathological inputs), larger leaves are allowed before giving up.
    for (uint32_t leaf_size : {options.max_leaf_size, uint32_t(RTC_BUILD_MAX_PRIMITIVES_PER_LEAF)}) {
      if (bvh) rtcReleaseBVH(bvh);
      bvh = rtcNewBVH(device);
      work = prims;  // the builder reorders (and with spatial splits appends to) the array
      work.resize(options.spatial_splits ? 2 * prim_count : prim_count);
      RTCBuildArguments args = rtcDefaultBuildArguments();
      args.buildQuality = RTC_BUILD_QUALITY_HIGH;
      args.maxBranchingFactor = 2;
      args.maxDepth = BVH_STACK_SIZE;
      args.minLeafSize = 1;
      args.maxLeafSize = std::max(1u, std::min(leaf_size, uint32_t(RTC_BUILD_MAX_PRIMITIVES_PER_LEAF)));
      args.traversalCost = 1.0f;
      args.intersectionCost = 1.0f;
      args.bvh = bvh;
      args.primitives = work.data();
      args.primitiveCount = prim_count;
      args.primitiveArrayCapacity = work.size();  // > count selects the spatial-split builder
      args.createNode = create_node;
      args.setNodeChildren = set_children;
      args.setNodeBounds = set_bounds;
      args.createLeaf = create_leaf;
      args.splitPrimitive = options.spatial_splits ? split_triangle : nullptr;
      args.userPtr = &input;
      root = rtcBuildBVH(&args);
      if (root) break;
    }
    if (!root) {
      const int code = int(rtcGetDeviceError(device));
      rtcReleaseBVH(bvh);
      rtcReleaseDevice(device);
      throw Error("Embree could not build the BVH for the GPU backend (error " + std::to_string(code) +
                  "; depth limit " + std::to_string(BVH_STACK_SIZE) + ")");
    }
    out.nodes.reserve(2 * prim_count);
    out.triangles.reserve(options.spatial_splits ? prim_count + prim_count / 4 : prim_count);
    Flattener{scene, out}.emit(static_cast<const BuildNode*>(root), root_bounds, 0);
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    out.stats.node_count = uint32_t(out.nodes.size());
  }
  out.stats.triangle_refs = uint32_t(out.triangles.size());
  if (out.stats.max_depth > BVH_STACK_SIZE)
    throw Error("the GPU BVH is " + std::to_string(out.stats.max_depth) + " levels deep, more than the traversal stack (" +
                std::to_string(BVH_STACK_SIZE) + ")");
  out.stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {
FlatBvhQuery query_of(const FlatBvh& bvh, const Scene* scene) {
  if (bvh.stats.alpha_tested_refs > 0 && !scene)
    throw Error("a flat BVH with alpha-tested triangles traversed without its scene");
  return FlatBvhQuery{bvh, scene};
}
}  // namespace

FlatHit flat_bvh_intersect(const FlatBvh& bvh, vec3 origin, vec3 dir, float tmin, float tmax, const Scene* scene) {
  const glsl::BvhHit h = glsl::bvh_intersect(query_of(bvh, scene), origin, dir, tmin, tmax);
  if (h.triangle == BVH_STACK_OVERFLOW) throw Error("flat BVH traversal stack overflow (a tree not from build_flat_bvh?)");
  FlatHit hit;
  if (h.triangle == BVH_INVALID_TRIANGLE) return hit;
  hit.t = h.t;
  hit.triangle = h.triangle;
  hit.barycentric = vec2(h.u, h.v);
  return hit;
}

bool flat_bvh_occluded(const FlatBvh& bvh, vec3 origin, vec3 dir, float tmin, float tmax, const Scene* scene) {
  const uint32_t r = glsl::bvh_occluded(query_of(bvh, scene), origin, dir, tmin, tmax);
  if (r == BVH_STACK_OVERFLOW) throw Error("flat BVH traversal stack overflow (a tree not from build_flat_bvh?)");
  return r == BVH_OCCLUDED;
}

}  // namespace sst
