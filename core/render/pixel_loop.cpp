#include "core/render/pixel_loop.h"

#include <tbb/parallel_for.h>

#include <mutex>

#include "core/util/progress.h"

namespace sst {

void for_each_tile(int width, int height, bool quiet, const char* label, RayCounters& total,
                   const std::function<void(const Tile&, RayCounters&)>& fn) {
  constexpr int kTile = 16;
  int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  int tiles = tiles_x * tiles_y;
  Progress progress(label, uint64_t(tiles), quiet);
  std::mutex merge;
  tbb::parallel_for(0, tiles, [&](int tile) {
    int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
    RayCounters local;
    fn(Tile{x0, y0, std::min(x0 + kTile, width), std::min(y0 + kTile, height)}, local);
    {
      std::lock_guard lock(merge);
      total += local;
    }
    progress.advance();
  });
  progress.finish();
}

void for_each_pixel(int width, int height, bool quiet, const char* label, RayCounters& total,
                    const std::function<void(int, int, RayCounters&)>& fn) {
  for_each_tile(width, height, quiet, label, total, [&](const Tile& tile, RayCounters& counters) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) fn(x, y, counters);
  });
}

}  // namespace sst
