// Runs a per-pixel or per-tile function over the image in parallel 16x16 tiles (oneTBB), with progress.
// Each pixel's result depends only on its own counter-based random numbers, so the image is the
// same bits whatever the thread count.
#pragma once
#include <functional>

#include "core/render/frame.h"

namespace sst {

// A rectangle of pixels [x0, x1) x [y0, y1).
struct Tile {
  int x0, y0, x1, y1;
  int width() const { return x1 - x0; }
  int pixels() const { return (x1 - x0) * (y1 - y0); }
};

// fn(tile, counters) renders the 16x16 tile (smaller at the image's right and bottom edges),
// counting into `counters`, which are summed into `total`; tiles run in parallel.
void for_each_tile(int width, int height, bool quiet, const char* label, RayCounters& total,
                   const std::function<void(const Tile& tile, RayCounters& counters)>& fn);

// fn(x, y, counters) renders pixel (x, y) into whatever the caller captured, counting into the
// tile-local `counters`, which are summed into `total`.
void for_each_pixel(int width, int height, bool quiet, const char* label, RayCounters& total,
                    const std::function<void(int x, int y, RayCounters& counters)>& fn);

}  // namespace sst
