// Where secondary and shadow rays start and end (shared C++/GLSL source): a surface point is lifted
// along its geometric normal by a scene-relative distance (scene_ray_epsilon: 1e-5 of the scene
// diagonal) plus a few float ulps of its magnitude (for scenes far from the origin), never an
// absolute one, so millimetre and kilometre scenes behave the same.
#ifndef SST_CORE_ACCEL_RAY_OFFSET_H
#define SST_CORE_ACCEL_RAY_OFFSET_H
#include "core/math/vector_math.h"

SST_BEGIN

SST_FUNC float ray_offset_distance(float scene_epsilon, vec3 p) {
  SST_PRECISE float e = scene_epsilon + 1e-6f * max_component(abs(p));
  return e;
}

// p lifted toward the side ng_toward points to.
SST_FUNC vec3 offset_ray_origin(float scene_epsilon, vec3 p, vec3 ng_toward) {
  SST_PRECISE vec3 r = p + ng_toward * ray_offset_distance(scene_epsilon, p);
  return r;
}

// A shadow ray between surface point p (geometric normal ng_p, on the side of y) and y: origin +
// t dir for t in [0, tmax], tmax just short of 1. Both ends are lifted off their surfaces (ng_y = 0
// for a point light, which has no surface): offsetting only the origin and shortening tmax by a
// constant fails at grazing angles, where the lifted ray meets the light's own plane up to
// eps / cos(theta) early and reports the light as its own occluder.
SST_FUNC void shadow_ray_segment(float scene_epsilon, vec3 p, vec3 ng_p, vec3 y, vec3 ng_y, SST_OUT(vec3) origin,
                                 SST_OUT(vec3) dir, SST_OUT(float) tmax) {
  origin = offset_ray_origin(scene_epsilon, p, ng_p);
  SST_PRECISE vec3 py = p - y;
  vec3 target = dot3(ng_y, py) < 0.0f ? offset_ray_origin(scene_epsilon, y, -ng_y)
                                      : offset_ray_origin(scene_epsilon, y, ng_y);
  SST_PRECISE vec3 d = target - origin;
  dir = d;
  tmax = 1.0f - 1e-4f;
}

SST_END

#endif  // SST_CORE_ACCEL_RAY_OFFSET_H
