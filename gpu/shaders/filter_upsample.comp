#version 450
#extension GL_GOOGLE_include_directive : require
// Joint bilateral upsampling (core/filter/upsample_kernel.h).
// Bindings: 0 low-resolution colour (RGB floats), 1 its depth, 2 its normal (RGB), 3 depth,
// 4 normal (RGB), 5 colour out, at full resolution.
#include "core/filter/filter_layout.h"
layout(std430, binding = 0) readonly buffer LowColor { float low_color_in[]; };
layout(std430, binding = 1) readonly buffer LowDepth { float low_depth_in[]; };
layout(std430, binding = 2) readonly buffer LowNormal { float low_normal_in[]; };
layout(std430, binding = 3) readonly buffer Depth { float depth_in[]; };
layout(std430, binding = 4) readonly buffer Normal { float normal_in[]; };
layout(std430, binding = 5) writeonly buffer ColorOut { float color_out[]; };
layout(push_constant) uniform Push { UpsamplePush push; };
#define FILTER_CTX_PARAM
#define FILTER_CTX
#define FILTER_COLOR(i) vec3(low_color_in[3 * (i)], low_color_in[3 * (i) + 1], low_color_in[3 * (i) + 2])
#define FILTER_LOW_DEPTH(i) low_depth_in[i]
#define FILTER_LOW_NORMAL(i) vec3(low_normal_in[3 * (i)], low_normal_in[3 * (i) + 1], low_normal_in[3 * (i) + 2])
#define FILTER_DEPTH(i) depth_in[i]
#define FILTER_NORMAL(i) vec3(normal_in[3 * (i)], normal_in[3 * (i) + 1], normal_in[3 * (i) + 2])
#include "core/filter/upsample_kernel.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= push.width || xy.y >= push.height) return;
  vec3 c = upsample_pixel(push, int(xy.x), int(xy.y));
  uint i = xy.y * push.width + xy.x;
  color_out[3u * i] = c.x;
  color_out[3u * i + 1u] = c.y;
  color_out[3u * i + 2u] = c.z;
}
