// What the filter kernels share (shared C++/GLSL source): the hooks through which they read their
// images, the B3-spline taps, and which pixels may be taps (inside, and seeing a surface).
//
// A kernel reads pixel i (= y * width + x) of its images only through these hooks; C++ defines them
// in filter_inputs.h, a shader before including a kernel (gpu/shaders/filter_*.comp):
//   FILTER_CTX_PARAM, FILTER_CTX   the leading parameter and argument of every kernel function that
//                                  reads images (C++: `const FilterInputs& fi,`; GLSL: empty)
//   FILTER_COLOR(i)       vec3   the image being filtered (the low-resolution one when upsampling)
//   FILTER_VARIANCE(i)    float  its luminance variance (SVGF)
//   FILTER_MOMENTS(i)     vec2   E[l], E[l^2] accumulated over time (SVGF)
//   FILTER_HISTORY(i)     float  frames of history behind the moments (SVGF)
//   FILTER_DEPTH(i)       float  distance from the camera to the first hit, 0 where nothing was hit
//   FILTER_NORMAL(i)      vec3   world-space shading normal
//   FILTER_LOW_DEPTH(i), FILTER_LOW_NORMAL(i)   the low-resolution G-buffer (upsampling)
// Each kernel file uses only some of them; a shader defines those its kernel file uses.
// The kernels return the filtered pixel; the driver (CPU loop or shader main) stores it, never into
// an image the same dispatch reads.
#ifndef SST_CORE_FILTER_FILTER_KERNEL_COMMON_H
#define SST_CORE_FILTER_FILTER_KERNEL_COMMON_H
#include "core/filter/filter_layout.h"
#include "core/math/vector_math.h"
#ifdef __cplusplus
#include "core/filter/filter_inputs.h"
namespace sst {
using glsl::AtrousPush;
using glsl::SvgfPush;
using glsl::UpsamplePush;
}  // namespace sst
#endif

SST_BEGIN

// The 1D B3-spline kernel (1, 4, 6, 4, 1) / 16 at tap k in -2..2; the 5x5 kernel is its product.
SST_FUNC float filter_b3(int k) {
  int a = k < 0 ? -k : k;
  return a == 0 ? 0.375f : (a == 1 ? 0.25f : 0.0625f);
}

// A pixel whose camera ray hit nothing (depth 0) is neither filtered nor used as a tap: sky and
// background keep their values, and surfaces never blend with them.
SST_FUNC bool filter_has_surface(float depth) { return depth > 0.0f; }

// Albedo demodulation (SVGF): the filters smooth the illumination, not the texture. Each channel
// divides by the albedo clamped to at least 0.01, a continuous divisor whose inverse remodulates
// exactly. A smaller floor would let light that does not scale with albedo (a dielectric's
// specular highlight on a black surface) become an illumination hundreds of times its neighbours'
// that the filters spread onto them. (A threshold below which channels were left undivided made
// SVGF's feedback unstable: illumination spread onto an undivided pixel was written back as its
// radiance, a thousand times what the surface reflects, and divided again the next frame.)
SST_FUNC vec3 filter_albedo_divisor(vec3 albedo) { return max(albedo, vec3(0.01f, 0.01f, 0.01f)); }

SST_FUNC bool filter_inside(int x, int y, int width, int height) { return x >= 0 && y >= 0 && x < width && y < height; }

// The index of pixel (x, y) if it is inside the image and sees a surface, else -1: a tap to use.
SST_FUNC int filter_surface_tap(FILTER_CTX_PARAM int x, int y, int width, int height) {
  if (!filter_inside(x, y, width, height)) return -1;
  int j = y * width + x;
  return filter_has_surface(FILTER_DEPTH(j)) ? j : -1;
}

SST_END

#endif  // SST_CORE_FILTER_FILTER_KERNEL_COMMON_H
