// A virtual point light (instant radiosity, Keller 1997; METHODS.md §1): a point on a diffuse
// surface that re-emits the light it received, with a cosine lobe about its normal. It emits
// intensity * max(0, n . w) in direction w (W/sr per RGB channel).
#pragma once
#include <vector>

#include "core/math/math.h"

namespace sst {

struct Vpl {
  vec3 position{0.0f};
  vec3 normal{0.0f, 0.0f, 1.0f};  // unit, on the side the light arrived from
  vec3 intensity{0.0f};           // throughput * albedo / pi
};

using VplSet = std::vector<Vpl>;

}  // namespace sst
