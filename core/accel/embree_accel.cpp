#include "core/accel/embree_accel.h"

#include "core/accel/flat_bvh.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/scene_access.h"
#include "core/scene/triangle_attributes.h"
#include "core/util/error.h"

namespace sst {
namespace {

bool has_alpha_test(const Scene& scene) {
  for (const Material& m : scene.materials)
    if (material_alpha_cutoff(m) > 0.0f) return true;
  return false;
}

// Embree's filter for intersection and occlusion queries alike: a hit that fails the alpha test
// is rejected, and the traversal goes on.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto& scene = *static_cast<const Scene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
    if (!triangle_alpha_tested(scene, triangle)) continue;
    const vec2 b(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    if (!triangle_alpha_passes(scene, triangle, b)) args->valid[i] = 0;
  }
}

}  // namespace

EmbreeAccel::EmbreeAccel(const Scene& scene, bool flat)
    : epsilon_(scene_ray_epsilon(scene)), alpha_scene_(has_alpha_test(scene) ? &scene : nullptr) {
  // One structure per accel: the flat BVH answers every query when it is there.
  if (flat)
    flat_ = std::make_unique<FlatBvh>(build_flat_bvh(scene));
  else
    build_embree(scene);
}

void EmbreeAccel::build_embree(const Scene& scene) {
  device_ = rtcNewDevice("");
  if (!device_) throw Error("could not create an Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  // Not RTC_SCENE_FLAG_ROBUST: it cost 15% of path-tracing time on the staircase and changed
  // no figure of the Cornell-box reference check (mean and RMSE identical to 5 digits).

  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree reads vertices with 16-byte loads, so the buffer it allocates has the padding it needs.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), scene.positions.size()));
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    vertices[3 * i + 0] = scene.positions[i].x;
    vertices[3 * i + 1] = scene.positions[i].y;
    vertices[3 * i + 2] = scene.positions[i].z;
  }
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), scene.triangles.size()));
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    indices[3 * i + 0] = scene.triangles[i].x;
    indices[3 * i + 1] = scene.triangles[i].y;
    indices[3 * i + 2] = scene.triangles[i].z;
  }
  if (alpha_scene_) {
    rtcSetGeometryUserData(geometry, const_cast<Scene*>(alpha_scene_));
    rtcSetGeometryIntersectFilterFunction(geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, alpha_filter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  // Embree reports failures (out of memory, invalid buffers) through the device, not by
  // exceptions: check once after the build, where they would surface.
  if (RTCError code = rtcGetDeviceError(device_); code != RTC_ERROR_NONE)
    throw Error("Embree could not build the acceleration structure (error " + std::to_string(int(code)) + ")");
}

float scene_ray_epsilon(const Scene& scene) {
  if (scene.positions.empty()) return 0.0f;
  const float m = max_component(glm::max(glm::abs(scene.bounds.lo), glm::abs(scene.bounds.hi)));
  return std::isfinite(m) ? 4.0f * kGamma7 * m : 0.0f;
}

EmbreeAccel::~EmbreeAccel() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

namespace {
RTCRay to_rtc(const Ray& ray) {
  RTCRay r;
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = ray.tmin;
  r.tfar = ray.tmax;
  r.time = 0.0f;
  r.mask = UINT32_MAX;
  r.id = 0;
  r.flags = 0;
  return r;
}
}  // namespace

Hit EmbreeAccel::intersect(const Ray& ray) const {
  if (log_) [[unlikely]]
    log_->add({ray.origin, ray.tmin, ray.direction, ray.tmax, false});
  if (flat_) return flat_bvh_intersect(*flat_, ray.origin, ray.direction, ray.tmin, ray.tmax, alpha_scene_);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = to_rtc(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rh.ray.tfar;
  hit.triangle = rh.hit.primID;
  hit.barycentric = {rh.hit.u, rh.hit.v};
  return hit;
}

bool EmbreeAccel::occluded(const Ray& ray) const {
  if (log_) [[unlikely]]
    log_->add({ray.origin, ray.tmin, ray.direction, ray.tmax, true});
  if (flat_) return flat_bvh_occluded(*flat_, ray.origin, ray.direction, ray.tmin, ray.tmax, alpha_scene_);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_rtc(ray);
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

RayBatchApi parse_ray_batch_api(const std::string& name) {
  if (name == "single") return RayBatchApi::single;
  if (name == "stream") return RayBatchApi::stream;
  if (name == "packet8") return RayBatchApi::packet8;
  if (name == "packet16") return RayBatchApi::packet16;
  throw Error("unknown batch_rays '" + name + "' (valid: single, stream, packet8, packet16)");
}

namespace {

template <int N>
void set_packet_ray(RTCRayNt<N>& packet, int lane, const Ray& ray) {
  packet.org_x[lane] = ray.origin.x;
  packet.org_y[lane] = ray.origin.y;
  packet.org_z[lane] = ray.origin.z;
  packet.tnear[lane] = ray.tmin;
  packet.dir_x[lane] = ray.direction.x;
  packet.dir_y[lane] = ray.direction.y;
  packet.dir_z[lane] = ray.direction.z;
  packet.time[lane] = 0.0f;
  packet.tfar[lane] = ray.tmax;
  packet.mask[lane] = UINT32_MAX;
  packet.id[lane] = 0;
  packet.flags[lane] = 0;
}

// The packet of rays[first ..]: at most N rays, the last one repeated in the lanes past `count`,
// which `valid` marks off. Returns how many lanes hold rays.
template <int N>
int fill_packet(RTCRayNt<N>& packet, int* valid, const Ray* rays, size_t first, size_t count) {
  const int lanes = int(std::min<size_t>(N, count - first));
  for (int i = 0; i < N; ++i) {
    valid[i] = i < lanes ? -1 : 0;
    set_packet_ray(packet, i, rays[first + size_t(std::min(i, lanes - 1))]);
  }
  return lanes;
}

// Packets of N rays through rtcIntersectN / rtcOccludedN (N = 8 or 16); the last one partly valid.
template <int N>
void intersect_packets(RTCScene scene, const Ray* rays, size_t count, Hit* hits) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (size_t first = 0; first < count; first += N) {
    alignas(64) RTCRayHitNt<N> packet;
    alignas(64) int valid[N];
    const int lanes = fill_packet<N>(packet.ray, valid, rays, first, count);
    for (int i = 0; i < N; ++i) {
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    if constexpr (N == 8)
      rtcIntersect8(valid, scene, &context, reinterpret_cast<RTCRayHit8*>(&packet));
    else
      rtcIntersect16(valid, scene, &context, reinterpret_cast<RTCRayHit16*>(&packet));
    for (int i = 0; i < lanes; ++i) {
      Hit& hit = hits[first + size_t(i)];
      hit = Hit{};
      if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
      hit.t = packet.ray.tfar[i];
      hit.triangle = packet.hit.primID[i];
      hit.barycentric = {packet.hit.u[i], packet.hit.v[i]};
    }
  }
}

template <int N>
void occluded_packets(RTCScene scene, const Ray* rays, size_t count, bool* occluded) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (size_t first = 0; first < count; first += N) {
    alignas(64) RTCRayNt<N> packet;
    alignas(64) int valid[N];
    const int lanes = fill_packet<N>(packet, valid, rays, first, count);
    if constexpr (N == 8)
      rtcOccluded8(valid, scene, &context, reinterpret_cast<RTCRay8*>(&packet));
    else
      rtcOccluded16(valid, scene, &context, reinterpret_cast<RTCRay16*>(&packet));
    for (int i = 0; i < lanes; ++i) occluded[first + size_t(i)] = packet.tfar[i] < 0.0f;
  }
}

}  // namespace

void EmbreeAccel::intersect(const Ray* rays, size_t count, Hit* hits, RayBatchApi api) const {
  if (flat_ || log_ || api == RayBatchApi::single) {
    for (size_t i = 0; i < count; ++i) hits[i] = intersect(rays[i]);
    return;
  }
  if (api == RayBatchApi::packet8) return intersect_packets<8>(scene_, rays, count, hits);
  if (api == RayBatchApi::packet16) return intersect_packets<16>(scene_, rays, count, hits);
  constexpr size_t kChunk = 256;  // a stream's RTCRayHits on the stack
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (size_t first = 0; first < count; first += kChunk) {
    RTCRayHit stream[kChunk];
    const size_t n = std::min(kChunk, count - first);
    for (size_t i = 0; i < n; ++i) {
      stream[i].ray = to_rtc(rays[first + i]);
      stream[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      stream[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(scene_, &context, stream, unsigned(n), sizeof(RTCRayHit));
    for (size_t i = 0; i < n; ++i) {
      Hit& hit = hits[first + i];
      hit = Hit{};
      if (stream[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      hit.t = stream[i].ray.tfar;
      hit.triangle = stream[i].hit.primID;
      hit.barycentric = {stream[i].hit.u, stream[i].hit.v};
    }
  }
}

void EmbreeAccel::occluded(const Ray* rays, size_t count, bool* occluded_out, RayBatchApi api) const {
  if (flat_ || log_ || api == RayBatchApi::single) {
    for (size_t i = 0; i < count; ++i) occluded_out[i] = occluded(rays[i]);
    return;
  }
  if (api == RayBatchApi::packet8) return occluded_packets<8>(scene_, rays, count, occluded_out);
  if (api == RayBatchApi::packet16) return occluded_packets<16>(scene_, rays, count, occluded_out);
  constexpr size_t kChunk = 256;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (size_t first = 0; first < count; first += kChunk) {
    RTCRay stream[kChunk];
    const size_t n = std::min(kChunk, count - first);
    for (size_t i = 0; i < n; ++i) stream[i] = to_rtc(rays[first + i]);
    rtcOccluded1M(scene_, &context, stream, unsigned(n), sizeof(RTCRay));
    for (size_t i = 0; i < n; ++i) occluded_out[first + i] = stream[i].tfar < 0.0f;
  }
}

size_t EmbreeAccel::replay(const RecordedRay* rays, size_t count, RayBatchApi api) const {
  size_t hits = 0;
  if (api == RayBatchApi::single) {
    for (size_t i = 0; i < count; ++i) {
      const RecordedRay& r = rays[i];
      Ray ray;
      ray.origin = r.origin;
      ray.direction = r.direction;
      ray.tmin = r.tmin;
      ray.tmax = r.tmax;
      hits += r.occlusion ? occluded(ray) : intersect(ray).valid();
    }
    return hits;
  }
  std::vector<Ray> batch;
  std::vector<Hit> found;
  std::unique_ptr<bool[]> blocked(new bool[count]);
  for (size_t first = 0; first < count;) {
    // The run of rays of one kind starting at `first`.
    size_t end = first + 1;
    while (end < count && rays[end].occlusion == rays[first].occlusion) ++end;
    batch.resize(end - first);
    for (size_t i = first; i < end; ++i) {
      Ray& ray = batch[i - first];
      ray.origin = rays[i].origin;
      ray.direction = rays[i].direction;
      ray.tmin = rays[i].tmin;
      ray.tmax = rays[i].tmax;
    }
    if (rays[first].occlusion) {
      occluded(batch.data(), batch.size(), blocked.get(), api);
      for (size_t i = 0; i < batch.size(); ++i) hits += blocked[i];
    } else {
      found.resize(batch.size());
      intersect(batch.data(), batch.size(), found.data(), api);
      for (const Hit& h : found) hits += h.valid();
    }
    first = end;
  }
  return hits;
}

}  // namespace sst
