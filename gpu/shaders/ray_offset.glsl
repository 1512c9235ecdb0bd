// The GLSL twin of EmbreeAccel's ray offsets (core/accel/embree_accel.h): secondary rays start a
// scene-relative distance off their surface, and shadow rays run between two lifted end points.
// The includer defines SCENE_RAY_EPSILON (EmbreeAccel's epsilon_: 1e-5 of the scene diagonal, see
// scene_ray_epsilon() in core/accel/embree_accel.h) before including this file.
#ifndef SST_GPU_SHADERS_RAY_OFFSET_GLSL
#define SST_GPU_SHADERS_RAY_OFFSET_GLSL
#include "core/math/vector_math.h"

#ifndef SCENE_RAY_EPSILON
#error "define SCENE_RAY_EPSILON before including gpu/shaders/ray_offset.glsl"
#endif

float ray_epsilon(vec3 p) {
  precise float e = SCENE_RAY_EPSILON + 1e-6 * max_component(abs(p));
  return e;
}

vec3 offset_point(vec3 p, vec3 ng_toward) {
  precise vec3 r = p + ng_toward * ray_epsilon(p);
  return r;
}

// EmbreeAccel::shadow_ray: from p (lifted along ng_p) to y (lifted to p's side of ng_y; ng_y = 0
// for a point light); the ray is origin + t dir for t in [0, tmax], tmax just short of 1.
void shadow_ray(vec3 p, vec3 ng_p, vec3 y, vec3 ng_y, out vec3 origin, out vec3 dir, out float tmax) {
  origin = offset_point(p, ng_p);
  precise vec3 py = p - y;
  vec3 target = dot3(ng_y, py) < 0.0 ? offset_point(y, -ng_y) : offset_point(y, ng_y);
  precise vec3 d = target - origin;
  dir = d;
  tmax = 1.0 - 1e-4;
}

#endif
