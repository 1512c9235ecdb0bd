#include "core/render/view_length.h"

#include <algorithm>

namespace sst {

float median_distance(std::vector<float> distances) {
  if (distances.empty()) return 0.0f;
  auto middle = distances.begin() + std::ptrdiff_t(distances.size() / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  return *middle;
}

float median_view_distance(const RenderContext& ctx) {
  std::vector<float> distances;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 16; ++i) {
      Ray ray = ctx.camera.generate(float((2 * i + 1) * ctx.width) / 32.0f, float((2 * j + 1) * ctx.height) / 18.0f);
      Hit hit = ctx.accel.intersect(ray);
      if (hit.valid()) distances.push_back(hit.t * glm::length(ray.direction));
    }
  return median_distance(std::move(distances));
}

}  // namespace sst
