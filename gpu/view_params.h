// The push constants every rendering shader starts with (core/render/frame_layout.h ViewParams),
// from the CPU's camera, so that both backends generate the same rays.
#pragma once
#include <cstdint>

#include "core/render/camera.h"
#include "core/render/frame_layout.h"

namespace sst::gpu {

// sample_offset 0 and spp 0: each dispatch sets its own range of sample indices.
inline glsl::ViewParams view_params(const PinholeCamera& camera, int width, int height, uint32_t seed) {
  PinholeCamera::Basis b = camera.basis();
  glsl::ViewParams p{};
  p.eye = b.eye;
  p.tan_half_y = b.tan_half_y;
  p.right = b.right;
  p.aspect = b.aspect;
  p.up = b.up;
  p.width = uint32_t(width);
  p.forward = b.forward;
  p.height = uint32_t(height);
  p.seed = seed;
  return p;
}

}  // namespace sst::gpu
