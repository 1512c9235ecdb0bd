#include "core/vpl/vpl_clamp.h"

namespace sst {

Bounds3 vpl_bounds(const VplSet& vpls) {
  Bounds3 b;
  for (const Vpl& v : vpls) b.extend(v.position);
  return b;
}

float vpl_clamp_distance(float clamp_fraction, const VplSet& vpls, const Scene& scene) {
  float d = vpl_bounds(vpls).diagonal();
  if (!(d > 0.0f) || !std::isfinite(d)) d = scene.bounds.diagonal();
  if (!(d > 0.0f) || !std::isfinite(d)) return 0.0f;
  return clamp_fraction * d;
}

}  // namespace sst
