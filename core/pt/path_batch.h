// `pt`'s paths on the CPU in batches: each thread keeps many paths in flight and advances them
// stage by stage (core/pt/path_stages.h), tracing each stage's rays together through Embree's ray
// streams or packets (EmbreeAccel's batch queries). Every path runs the same stages in the same
// order as when traced alone (trace_path_state), so the images are the same bits for any batch
// size; what changes is how the work meets the caches and Embree (docs/performance.md).
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "core/pt/path_tracer.h"
#include "core/render/pixel_loop.h"

namespace sst {

// One thread's storage for its batches, kept between them.
struct PathBatchScratch {
  std::vector<PathState> paths;
  std::vector<Ray> camera_rays;
  std::vector<uint32_t> active, traced;  // indices into the batch
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::unique_ptr<bool[]> occluded;  // a shadow-ray batch's answers (EmbreeAccel wants bool*)
  size_t occluded_size = 0;
};

// Traces `count` paths, each ready for its camera ray (path_begin), to their ends: every stage of
// the batch's live paths, then that stage's rays in one batch query (`api`).
void trace_path_batch(const RenderContext& context, const PathConfig& config, RayBatchApi api, PathState* paths,
                      size_t count, PathBatchScratch& scratch);

// Called for each camera path of a tile once it has ended: the pixel's index in the tile
// (row-major), the sample index, the camera ray and the path (its sampler where the path left it).
using PathFinish = std::function<void(int pixel, int sample, const Ray& camera_ray, PathState& path)>;

// Every camera path of the tile's pixels, context.options.spp each (pixel_sampler(seed, pixel, i),
// its jitter, the camera ray), in batches of context.options.path_batch paths (0: each path traced
// alone, trace_path_state). `finish` sees the paths pixel by pixel and each pixel's samples in
// order, so sums over them are the same floats whatever the batch. Each path's rays and the path
// itself (a sample) are counted into `counters`.
void trace_tile_paths(const RenderContext& context, const PathConfig& config, const Tile& tile, RayCounters& counters,
                      const PathFinish& finish);

}  // namespace sst
