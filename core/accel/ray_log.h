// The rays an EmbreeAccel is asked to trace, in the order each thread asked for them: a path
// tracer's own mix of camera, bounce and shadow rays, to replay through Embree alone
// (EmbreeAccel::replay). What a renderer costs beyond that replay is its own work: shading,
// sampling, texture fetches (tests/benchmarks/path_tracer_benchmark.cpp, issue 16's "Embree-only
// rate").
#pragma once
#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math/math.h"

namespace sst {

struct RecordedRay {
  vec3 origin;
  float tmin = 0.0f;
  vec3 direction;
  float tmax = kInf;
  bool occlusion = false;  // an occlusion query (rtcOccluded1); else a closest hit (rtcIntersect1)
};

// Thread-safe: each thread appends to its own list.
class RayLog {
 public:
  // Out of line and cold: the accel's queries only test for a log, so that their code and
  // inlining stay as they are without one.
  [[gnu::noinline, gnu::cold]] void add(const RecordedRay& ray);
  // Every thread's rays, one thread's after another's, each in the order traced; empties the log.
  std::vector<RecordedRay> take();

 private:
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> per_thread_;
};

// How many rays of each kind a log holds.
struct RayMix {
  size_t closest_hit = 0;
  size_t occlusion = 0;
};
RayMix ray_mix(const std::vector<RecordedRay>& rays);

}  // namespace sst
