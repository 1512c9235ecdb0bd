#version 450
#extension GL_GOOGLE_include_directive : require
// One pass of the edge-avoiding a-trous filter (core/filter/atrous_kernel.h).
// Bindings: 0 colour in (RGB floats), 1 depth, 2 normal (RGB), 3 colour out.
#include "core/filter/filter_layout.h"
layout(std430, binding = 0) readonly buffer ColorIn { float color_in[]; };
layout(std430, binding = 1) readonly buffer Depth { float depth_in[]; };
layout(std430, binding = 2) readonly buffer Normal { float normal_in[]; };
layout(std430, binding = 3) writeonly buffer ColorOut { float color_out[]; };
layout(push_constant) uniform Push { AtrousPush push; };
#define FILTER_CTX_PARAM
#define FILTER_CTX
#define FILTER_COLOR(i) vec3(color_in[3 * (i)], color_in[3 * (i) + 1], color_in[3 * (i) + 2])
#define FILTER_DEPTH(i) depth_in[i]
#define FILTER_NORMAL(i) vec3(normal_in[3 * (i)], normal_in[3 * (i) + 1], normal_in[3 * (i) + 2])
#include "core/filter/atrous_kernel.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= push.width || xy.y >= push.height) return;
  vec3 c = atrous_pixel(push, int(xy.x), int(xy.y));
  uint i = xy.y * push.width + xy.x;
  color_out[3u * i] = c.x;
  color_out[3u * i + 1u] = c.y;
  color_out[3u * i + 2u] = c.z;
}
