// Pinhole camera generating primary rays; pixel (0,0) is the top-left corner of the image.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/render/frame_layout.h"
#include "core/scene/scene.h"

namespace sst {

class PinholeCamera {
 public:
  PinholeCamera(const Camera& camera, int width, int height);
  // (px, py) in pixels, continuous: pixel x covers [x, x+1). Unit-length direction.
  Ray generate(float px, float py) const;

  // What generate() computes from, for the GPU port (core/render/pinhole.h).
  struct Basis {
    vec3 eye, right, up, forward;
    float tan_half_y, aspect;
  };
  Basis basis() const { return {eye_, right_, up_, forward_, tan_half_y_, aspect_}; }

 private:
  vec3 eye_, right_, up_, forward_;
  float tan_half_y_ = 0.0f, aspect_ = 1.0f;
  int width_ = 1, height_ = 1;
};

// The view of `camera` as the shared kernels and every rendering shader read it (ViewParams of
// core/render/frame_layout.h), so that both backends generate the same rays. sample_offset and
// spp are 0: each dispatch sets its own range of sample indices.
glsl::ViewParams view_params(const PinholeCamera& camera, int width, int height, uint32_t seed);

// Picks a camera by name or index ("" = the first). Throws sst::Error listing what exists.
const Camera& select_camera(const Scene& scene, const std::string& name_or_index);
// Fills whichever of width/height is 0 from the other and the camera's aspect ratio (square
// when the camera has none); both 0 gives a width of 640.
void resolve_resolution(const Camera& camera, int& width, int& height);

}  // namespace sst
