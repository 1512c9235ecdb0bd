// Ray queries against the scene's triangles with Embree 3: closest hit and occlusion. Or, with
// `flat` (RenderOptions::accel = "flat"), with the flat BVH the Vulkan backend traverses
// (core/accel/flat_bvh.h): the same traversal code, so the CPU and GPU images can be compared bit
// for bit, without Embree's different barycentrics and edge decisions.
// Offsets that keep secondary rays off their own surface are bounds of the floating-point error of
// the points they start from (core/accel/ray_offset.h), never lengths taken from the scene's size.
#pragma once
#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <string>

#include "core/accel/bvh_layout.h"
#include "core/accel/ray_log.h"
#include "core/accel/ray_offset.h"
#include "core/math/math.h"
#include "core/scene/scene.h"

namespace sst {

struct Ray {
  vec3 origin;
  vec3 direction;  // need not be unit length; t is in units of |direction|
  float tmin = 0.0f;
  float tmax = kInf;
};

struct Hit {
  float t = kInf;
  uint32_t triangle = UINT32_MAX;
  vec2 barycentric{0.0f};  // Embree's (u, v): p = (1-u-v) p0 + u p1 + v p2
  bool valid() const { return triangle != UINT32_MAX; }
};

// The ray offset of a point known only by its coordinates (ray_offset.h): gamma(7) times twice the
// largest coordinate magnitude M of the scene's bounds, along each axis of a unit normal (at most
// sqrt(3) of them): 4 gamma(7) M, at least the triangle_point_offset of any point of any of the
// scene's triangles. The Vulkan backend uses the same value.
float scene_ray_epsilon(const Scene& scene);

struct FlatBvh;

// How a batch of rays (EmbreeAccel::intersect(const Ray*, ...)) goes to Embree: one rtcIntersect1
// per ray, one ray stream (rtcIntersect1M), or packets of 8 or 16 rays (rtcIntersect8/16). Each
// ray finds the same hit whichever is used (the choice is speed only: docs/performance.md); the
// flat BVH answers every ray alone.
enum class RayBatchApi { single, stream, packet8, packet16 };
RayBatchApi parse_ray_batch_api(const std::string& name);  // throws for an unknown name

// Alpha-tested triangles (glTF MASK and BLEND: triangle_alpha_passes, core/scene/triangle_attributes.h)
// are tested by every query, through Embree's filter functions or the flat BVH's hook, against
// `scene`, which must outlive the accel.
class EmbreeAccel {
 public:
  explicit EmbreeAccel(const Scene& scene, bool flat = false);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  // The flat BVH the queries use, or null when they use Embree.
  const FlatBvh* flat_bvh() const { return flat_.get(); }

  Hit intersect(const Ray& ray) const;
  bool occluded(const Ray& ray) const;
  // A batch: hits[i] (occluded[i]) for rays[i], as intersect() (occluded()) would answer. Not in
  // Embree's coherent mode: it was 3% faster on camera rays, but chose the other of two coplanar
  // triangles at some pixels of the breakfast room, so the images would depend on the batch.
  void intersect(const Ray* rays, size_t count, Hit* hits, RayBatchApi api) const;
  void occluded(const Ray* rays, size_t count, bool* occluded, RayBatchApi api) const;

  // While `log` is set, every query is also appended to it (one predictable branch per query when
  // it is not). The log must outlive its use; pass null to stop.
  void set_ray_log(RayLog* log) { log_ = log; }
  // Traces `rays` through Embree alone (or the flat BVH), on the calling thread: each ray by itself
  // (RayBatchApi::single), or each run of consecutive rays of one kind as one batch query, as a
  // batched path tracer hands them over. Returns how many found a hit, so that the work cannot be
  // optimised away. Not while a log is set: it would record them again.
  size_t replay(const RecordedRay* rays, size_t count, RayBatchApi api = RayBatchApi::single) const;

  // The ray offset of a point known only by its coordinates (scene_ray_epsilon).
  float scene_epsilon() const { return epsilon_; }
  // The shadow ray between point p (geometric normal ng_p, on the side of y) and y
  // (shadow_ray_segment, ray_offset.h; ng_y = 0 for a point light), both known only by their
  // coordinates (VPLs, substitute lights, shading points of the VPL methods).
  Ray shadow_ray(vec3 p, vec3 ng_p, vec3 y, vec3 ng_y) const {
    Ray ray;
    shadow_ray_segment(epsilon_, p, ng_p, epsilon_, y, ng_y, ray.origin, ray.direction, ray.tmax);
    ray.tmin = 0.0f;
    return ray;
  }

 private:
  void build_embree(const Scene& scene);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  float epsilon_ = 0.0f;
  const Scene* alpha_scene_ = nullptr;  // set when a material has an alpha test
  std::unique_ptr<FlatBvh> flat_;  // set: queries go to the flat BVH instead of Embree
  RayLog* log_ = nullptr;
};

// The RAY_* hooks of the shared path kernels (core/pt/trace_path.h): the closest hit along
// origin + t dir, t in [0, inf), in the GPU traversal's form (triangle BVH_INVALID_TRIANGLE for a
// miss), and whether anything lies on origin + t dir, t in [0, tmax).
inline BvhHit to_bvh_hit(const Hit& h) {
  BvhHit out;
  out.t = h.t;
  out.triangle = h.valid() ? h.triangle : BVH_INVALID_TRIANGLE;
  out.u = h.barycentric.x;
  out.v = h.barycentric.y;
  return out;
}

inline BvhHit accel_intersect(const EmbreeAccel& accel, vec3 origin, vec3 dir) {
  Ray ray;
  ray.origin = origin;
  ray.direction = dir;
  return to_bvh_hit(accel.intersect(ray));
}

inline bool accel_occluded(const EmbreeAccel& accel, vec3 origin, vec3 dir, float tmax) {
  Ray ray;
  ray.origin = origin;
  ray.direction = dir;
  ray.tmax = tmax;
  return accel.occluded(ray);
}

}  // namespace sst

#define RAY_CTX_PARAM const ::sst::EmbreeAccel &accel,
#define RAY_CTX accel,
#define RAY_INTERSECT(origin, dir) ::sst::accel_intersect(accel, origin, dir)
#define RAY_OCCLUDED(origin, dir, tmax) ::sst::accel_occluded(accel, origin, dir, tmax)
#define RAY_EPSILON accel.scene_epsilon()
