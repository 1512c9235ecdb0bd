// The G-buffer of a frame's pixel centres, for what works across frames and between pixels
// (temporal reuse, the G-buffer-guided filters, upsampling): for each pixel's centre ray the first
// hit's distance and shading normal, where the same surface point was one frame earlier (the hit
// triangle's vertices in the previous pose, seen by the previous camera), and its distance from
// that camera. Unlike the AOVs a method averages over its jittered samples, these do not change
// from frame to frame under a static view, so history is tested against the same values every
// frame. (Light is demodulated by the samples' own albedo instead: core/temporal/temporal_layout.h.)
#pragma once
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/image/image.h"
#include "core/render/frame_layout.h"
#include "core/scene/scene.h"

namespace sst {

struct CentreGBuffer {
  Image depth;    // distance from the camera to the first hit; 0 for a miss. 1 channel
  Image normal;   // shading normal facing the camera; 0 for a miss
  // Previous position minus current position of the point each pixel centre sees, in pixels (x
  // right, y down); for a miss, the motion of the direction (a point at infinity). 2 channels.
  Image motion;
  // That point's distance from the previous frame's camera; 0 for a miss or a point behind it.
  Image previous_depth;
};

// `previous_positions` are the scene's vertex positions one frame earlier (same topology);
// `view` and `previous_view` the cameras of the two frames (view_params of core/render/camera.h).
CentreGBuffer centre_gbuffer(const EmbreeAccel& accel, const Scene& scene, const std::vector<vec3>& previous_positions,
                             const glsl::ViewParams& view, const glsl::ViewParams& previous_view);

}  // namespace sst
