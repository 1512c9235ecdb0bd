#include "core/render/pixel_loop.h"

#include <tbb/parallel_for.h>

#include <mutex>

#include "core/util/progress.h"

namespace sst {

void for_each_pixel(int width, int height, bool quiet, const char* label, RayCounters& total,
                    const std::function<void(int, int, RayCounters&)>& fn) {
  constexpr int kTile = 16;
  int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  int tiles = tiles_x * tiles_y;
  Progress progress(label, uint64_t(tiles), quiet);
  std::mutex merge;
  tbb::parallel_for(0, tiles, [&](int tile) {
    int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
    RayCounters local;
    for (int y = y0; y < std::min(y0 + kTile, height); ++y)
      for (int x = x0; x < std::min(x0 + kTile, width); ++x) fn(x, y, local);
    {
      std::lock_guard lock(merge);
      total += local;
    }
    progress.advance();
  });
  progress.finish();
}

}  // namespace sst
