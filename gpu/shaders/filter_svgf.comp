#version 450
#extension GL_GOOGLE_include_directive : require
// SVGF's spatial stages (core/filter/svgf_kernel.h), one dispatch per push.pass: the variance
// estimate (writes binding 7) or one a-trous level (writes 6 and 7).
// Bindings: 0 illumination in (RGB floats), 1 variance in, 2 moments (2 floats), 3 history length,
// 4 depth, 5 normal (RGB), 6 illumination out, 7 variance out.
#include "core/filter/filter_layout.h"
layout(std430, binding = 0) readonly buffer ColorIn { float color_in[]; };
layout(std430, binding = 1) readonly buffer VarianceIn { float variance_in[]; };
layout(std430, binding = 2) readonly buffer Moments { float moments_in[]; };
layout(std430, binding = 3) readonly buffer History { float history_in[]; };
layout(std430, binding = 4) readonly buffer Depth { float depth_in[]; };
layout(std430, binding = 5) readonly buffer Normal { float normal_in[]; };
layout(std430, binding = 6) writeonly buffer ColorOut { float color_out[]; };
layout(std430, binding = 7) writeonly buffer VarianceOut { float variance_out[]; };
layout(push_constant) uniform Push { SvgfPush push; };
#define FILTER_CTX_PARAM
#define FILTER_CTX
#define FILTER_COLOR(i) vec3(color_in[3 * (i)], color_in[3 * (i) + 1], color_in[3 * (i) + 2])
#define FILTER_VARIANCE(i) variance_in[i]
#define FILTER_MOMENTS(i) vec2(moments_in[2 * (i)], moments_in[2 * (i) + 1])
#define FILTER_HISTORY(i) history_in[i]
#define FILTER_DEPTH(i) depth_in[i]
#define FILTER_NORMAL(i) vec3(normal_in[3 * (i)], normal_in[3 * (i) + 1], normal_in[3 * (i) + 2])
#include "core/filter/svgf_kernel.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= push.width || xy.y >= push.height) return;
  uint i = xy.y * push.width + xy.x;
  if (push.pass == SVGF_PASS_VARIANCE) {
    variance_out[i] = svgf_variance_pixel(push, int(xy.x), int(xy.y));
    return;
  }
  vec4 v = svgf_atrous_pixel(push, int(xy.x), int(xy.y));
  color_out[3u * i] = v.x;
  color_out[3u * i + 1u] = v.y;
  color_out[3u * i + 2u] = v.z;
  variance_out[i] = v.w;
}
