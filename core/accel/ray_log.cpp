#include "core/accel/ray_log.h"

namespace sst {

void RayLog::add(const RecordedRay& ray) { per_thread_.local().push_back(ray); }

std::vector<RecordedRay> RayLog::take() {
  std::vector<RecordedRay> all;
  size_t n = 0;
  for (const auto& rays : per_thread_) n += rays.size();
  all.reserve(n);
  for (auto& rays : per_thread_) {
    all.insert(all.end(), rays.begin(), rays.end());
    rays.clear();
    rays.shrink_to_fit();
  }
  return all;
}

RayMix ray_mix(const std::vector<RecordedRay>& rays) {
  RayMix mix;
  for (const RecordedRay& r : rays) (r.occlusion ? mix.occlusion : mix.closest_hit) += 1;
  return mix;
}

}  // namespace sst
