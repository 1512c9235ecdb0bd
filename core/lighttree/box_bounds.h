// Bounds of a light-tree node's box as seen from a shading point x: what every tree sampler's
// weights are built from (SLC, SST, RTSLC, the hybrid's cuts).
#pragma once
#include "core/math/math.h"

namespace sst {

// Squared distance from x to the box (0 inside; +inf for an empty box).
float box_distance2_min(const Bounds3& box, vec3 x);
// Squared distance from x to the farthest point of the box: sum over axes of
// max(|lo - x|, |hi - x|)^2 (RTSLC's dmax^2).
float box_distance2_max(const Bounds3& box, vec3 x);

// Upper bounds of max(0, n . normalize(y - x)) over the points y of the box, 1 when x is inside.
// Both are conservative; they trade tightness for cost:
// - box_cos_bound (Walter 2005): the corners are taken to n's frame and the bound is that of the
//   AABB of the transformed corners. Tight; used by slc and sst.
// - box_cos_bound_linear: min(1, max_y n.(y - x) / dmin), the exact maximum of a linear function
//   over the box over a lower bound of |y - x|. Cheap, tight for far boxes; used by rtslc's
//   weights and the cuts.
float box_cos_bound(const Bounds3& box, vec3 x, vec3 n);
float box_cos_bound_linear(const Bounds3& box, vec3 x, vec3 n);

}  // namespace sst
