// What one rendered frame produces: the image, its AOVs and the counters of the work done.
#pragma once
#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "core/image/image.h"

namespace sst {

// Ray and sample counts. Threads count into a local copy and merge once per tile.
struct RayCounters {
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  uint64_t bounce_rays = 0;
  uint64_t samples = 0;
  uint64_t nonfinite_samples = 0;  // samples discarded for a NaN/Inf value; should stay 0

  RayCounters& operator+=(const RayCounters& o);
  uint64_t total_rays() const { return primary_rays + shadow_rays + bounce_rays; }
  nlohmann::json to_json(double render_ms) const;  // adds Mrays/s from the render time
};

struct FrameOutput {
  Image color;     // direct + indirect
  Image direct;    // emission seen by the camera + direct light at the first hit
  Image indirect;  // everything else: what a GI method estimates
  Image albedo;    // base colour at the first hit
  Image normal;    // shading normal at the first hit (world space, facing the camera)
  Image depth;     // distance from the camera to the first hit (0 where nothing is hit), 1 channel
  std::vector<Layer> extra_layers;  // method-specific AOVs (variance, traversal depth, ...)
  RayCounters counters;
  nlohmann::json method_counters = nlohmann::json::object();  // method-specific (tree nodes visited, ...)

  void allocate(int width, int height);
  std::vector<Layer> layers() const;  // the AOVs as EXR layers
};

}  // namespace sst
