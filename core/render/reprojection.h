// Where a camera sees a world-space point (shared C++/GLSL source): the inverse of the pinhole's
// ray generation (core/render/pinhole.h), from which motion vectors and the previous frame's
// distance of a surface point are computed. Apart from pinhole.h so that the shaders that only
// generate rays do not compile it (glslang's `precise` propagation grows with every function).
#ifndef SST_CORE_RENDER_REPROJECTION_H
#define SST_CORE_RENDER_REPROJECTION_H
#include "core/math/vector_math.h"
#include "core/render/frame_layout.h"

#ifdef __cplusplus
namespace sst {
using glsl::ViewParams;
}
#endif

SST_BEGIN

// The continuous pixel position ((0, 0) the top-left corner, as pinhole_direction takes it) at
// which `view` sees point p, and p's distance from the eye; false when p is not in front of the
// camera (it has no position in the image).
SST_FUNC bool project_to_pixel(SST_IN(ViewParams) view, vec3 p, SST_OUT(vec2) pixel, SST_OUT(float) distance) {
  SST_PRECISE vec3 d = p - view.eye;
  float z = dot3(d, view.forward);
  distance = length3(d);
  pixel = vec2(0.0f, 0.0f);
  if (!(z > 0.0f)) return false;
  SST_PRECISE float sx = dot3(d, view.right) / (z * view.tan_half_y * view.aspect);
  SST_PRECISE float sy = dot3(d, view.up) / (z * view.tan_half_y);
  SST_PRECISE float px = (sx + 1.0f) * 0.5f * float(view.width);
  SST_PRECISE float py = (1.0f - sy) * 0.5f * float(view.height);
  pixel = vec2(px, py);
  return true;
}

// The same for a direction (a point at infinity, what a ray that hits nothing sees).
SST_FUNC bool project_direction_to_pixel(SST_IN(ViewParams) view, vec3 direction, SST_OUT(vec2) pixel) {
  float distance;
  ViewParams at_origin = view;
  at_origin.eye = vec3(0.0f, 0.0f, 0.0f);
  return project_to_pixel(at_origin, direction, pixel, distance);
}

SST_END

#endif  // SST_CORE_RENDER_REPROJECTION_H
