// The direction of a pinhole camera's ray through a point of the image (shared C++/GLSL source):
// PinholeCamera::generate on the CPU, the camera rays of every shader (camera_sample_direction).
#ifndef SST_CORE_RENDER_PINHOLE_H
#define SST_CORE_RENDER_PINHOLE_H
#include "core/math/vector_math.h"
#include "core/render/frame_layout.h"
#include "core/rng/sobol_sampler.h"

#ifdef __cplusplus
namespace sst {
using glsl::ViewParams;
}
#endif

SST_BEGIN

// (px, py) in pixels, continuous, (0, 0) the top-left corner; forward/right/up the camera's
// orthonormal axes. Unit direction.
SST_FUNC vec3 pinhole_direction(vec3 forward, vec3 right, vec3 up, float tan_half_y, float aspect, float width,
                                float height, float px, float py) {
  SST_PRECISE float sx = (2.0f * px / width - 1.0f) * tan_half_y * aspect;
  SST_PRECISE float sy = (1.0f - 2.0f * py / height) * tan_half_y;
  SST_PRECISE vec3 d = forward + sx * right + sy * up;
  return normalize3(d);
}

// The same with the camera of a dispatch's view parameters.
SST_FUNC vec3 camera_direction(SST_IN(ViewParams) view, float px, float py) {
  return pinhole_direction(view.forward, view.right, view.up, view.tan_half_y, view.aspect, float(view.width),
                           float(view.height), px, py);
}

// The direction of a camera sample through pixel (x, y): the pixel jittered by the sampler's next
// 2D point (a pixel sample's first), as the CPU's pixel loops jitter PinholeCamera::generate.
SST_FUNC vec3 camera_sample_direction(SST_IN(ViewParams) view, uint x, uint y, SST_INOUT(PixelSampler) ps) {
  vec2 jitter = pixel_sampler_get2d(ps);
  SST_PRECISE float px = float(x) + jitter.x;
  SST_PRECISE float py = float(y) + jitter.y;
  return camera_direction(view, px, py);
}

SST_END

#endif  // SST_CORE_RENDER_PINHOLE_H
