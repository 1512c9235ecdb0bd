#include "core/render/frame.h"

namespace sst {

RayCounters& RayCounters::operator+=(const RayCounters& o) {
  primary_rays += o.primary_rays;
  shadow_rays += o.shadow_rays;
  bounce_rays += o.bounce_rays;
  samples += o.samples;
  nonfinite_samples += o.nonfinite_samples;
  return *this;
}

nlohmann::json RayCounters::to_json(double render_ms) const {
  nlohmann::json j;
  j["primary_rays"] = primary_rays;
  j["shadow_rays"] = shadow_rays;
  j["bounce_rays"] = bounce_rays;
  j["total_rays"] = total_rays();
  j["samples"] = samples;
  j["nonfinite_samples"] = nonfinite_samples;
  j["mrays_per_s"] = render_ms > 0.0 ? double(total_rays()) / (render_ms * 1e3) : 0.0;
  return j;
}

void FrameOutput::allocate(int width, int height) {
  color = Image(width, height);
  direct = Image(width, height);
  indirect = Image(width, height);
  albedo = Image(width, height);
  normal = Image(width, height);
  depth = Image(width, height, 1);
}

std::vector<Layer> FrameOutput::layers() const {
  std::vector<Layer> all = {
      {"direct", direct}, {"indirect", indirect}, {"albedo", albedo}, {"normal", normal}, {"depth", depth}};
  all.insert(all.end(), extra_layers.begin(), extra_layers.end());
  return all;
}

}  // namespace sst
