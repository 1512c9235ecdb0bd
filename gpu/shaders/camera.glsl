// GLSL port of PinholeCamera::generate (core/render/camera.cpp), same expression order.
// Needs `frame` (FrameParams, core/render/frame_layout.h) in scope.
#ifndef SST_CAMERA_GLSL
#define SST_CAMERA_GLSL
#include "core/math/vector_math.h"

// (px, py) in pixels, continuous, (0,0) the top-left corner. Unit direction.
vec3 camera_direction(FrameParams frame, float px, float py) {
  precise float sx = (2.0 * px / float(frame.width) - 1.0) * frame.tan_half_y * frame.aspect;
  precise float sy = (1.0 - 2.0 * py / float(frame.height)) * frame.tan_half_y;
  precise vec3 d = frame.forward + sx * frame.right + sy * frame.up;
  return normalize3(d);
}

#endif
