#include "core/math/morton.h"

#include <cmath>

namespace sst {

MortonGrid MortonGrid::over(const Bounds3& bounds) {
  MortonGrid grid;
  if (bounds.empty()) return grid;
  grid.origin = bounds.lo;
  vec3 extent = bounds.hi - bounds.lo;
  for (int axis = 0; axis < 3; ++axis) {
    float s = extent[axis] > 0.0f ? 1024.0f / extent[axis] : 0.0f;
    // A denormal extent would overflow the scale; such an axis counts as degenerate.
    grid.scale[axis] = std::isfinite(s) ? s : 0.0f;
  }
  return grid;
}

}  // namespace sst
