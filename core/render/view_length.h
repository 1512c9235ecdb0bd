// The size of what a view sees, whatever lies beyond it (docs/design/lengths.md). A length that
// should scale with the scene but must not change when a ground plane, a sky dome or a far prop
// is added outside the view is a multiple of this one, not of a bounding box: the VPL methods'
// light-tree length D and directional-light focus, GI-1.0's cache cell sizes.
#pragma once
#include <vector>

#include "core/render/method.h"

namespace sst {

// The median distance from the camera to what a grid of 16 x 9 pixel-centre rays hits; 0 when
// every ray misses.
float median_view_distance(const RenderContext& context);

// The median of `distances` (taken by value: it is reordered); 0 for none.
float median_distance(std::vector<float> distances);

}  // namespace sst
