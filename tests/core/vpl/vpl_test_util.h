// Shared by the VPL tests: analytic light powers and simple sample statistics.
#pragma once
#include <cmath>
#include <memory>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"

namespace sst::test {

// A scene with its acceleration structure and light sampler (which point into the scene).
struct PreparedScene {
  Scene scene;
  std::unique_ptr<EmbreeAccel> accel;
  std::unique_ptr<LightSampler> lights;
  explicit PreparedScene(Scene s) : scene(std::move(s)) {
    accel = std::make_unique<EmbreeAccel>(scene);
    lights = std::make_unique<LightSampler>(scene);
  }
};

// Flux of a spot light per unit intensity: 2 pi * integral over cos theta in [-1, 1] of the glTF
// attenuation (smoothstep-free linear ramp, squared), by the midpoint rule in double.
inline double spot_flux_per_intensity(const PunctualLight& spot) {
  const int n = 1 << 20;
  double scale = 1.0 / std::max(0.001, double(spot.cos_inner) - double(spot.cos_outer));
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    double c = -1.0 + 2.0 * (i + 0.5) / n;
    double a = std::clamp((c - double(spot.cos_outer)) * scale, 0.0, 1.0);
    sum += a * a;
  }
  return 2.0 * M_PI * sum * 2.0 / n;
}

// Mean and standard error of the mean.
struct MeanError {
  double mean = 0.0, error = 0.0;
};
inline MeanError mean_error(const std::vector<double>& x) {
  double sum = 0.0, sum2 = 0.0;
  for (double v : x) sum += v;
  double mean = sum / double(x.size());
  for (double v : x) sum2 += (v - mean) * (v - mean);
  double var = x.size() > 1 ? sum2 / double(x.size() - 1) : 0.0;
  return {mean, std::sqrt(var / double(x.size()))};
}

}  // namespace sst::test
