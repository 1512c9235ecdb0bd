// Runs a per-pixel function over the image in parallel 16x16 tiles (oneTBB), with progress.
// Each pixel's result depends only on its own counter-based random numbers, so the image is the
// same bits whatever the thread count.
#pragma once
#include <functional>

#include "core/render/frame.h"

namespace sst {

// fn(x, y, counters) renders pixel (x, y) into whatever the caller captured, counting into the
// tile-local `counters`, which are summed into `total`.
void for_each_pixel(int width, int height, bool quiet, const char* label, RayCounters& total,
                    const std::function<void(int x, int y, RayCounters& counters)>& fn);

}  // namespace sst
