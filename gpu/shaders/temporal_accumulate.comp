#version 450
#extension GL_GOOGLE_include_directive : require
// Temporal reuse of one frame (core/temporal/temporal_accumulate.h).
// Bindings: 0 the frame's TemporalInput per pixel, 1 the previous history, 2 the new history.
#include "core/temporal/temporal_layout.h"
layout(std430, binding = 0) readonly buffer Input { TemporalInput frame_input[]; };
layout(std430, binding = 1) readonly buffer HistoryIn { TemporalTexel history_in[]; };
layout(std430, binding = 2) writeonly buffer HistoryOut { TemporalTexel history_out[]; };
layout(push_constant) uniform Push { TemporalPush push; };
#define TEMPORAL_CTX_PARAM
#define TEMPORAL_HISTORY(i) history_in[i]
#include "core/temporal/temporal_accumulate.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= push.width || xy.y >= push.height) return;
  uint i = xy.y * push.width + xy.x;
  history_out[i] = temporal_accumulate_pixel(int(xy.x), int(xy.y), frame_input[i], push);
}
