#include "core/render/camera.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "core/render/pinhole.h"
#include "core/util/error.h"

namespace sst {

PinholeCamera::PinholeCamera(const Camera& camera, int width, int height)
    : eye_(camera.eye), width_(width), height_(height) {
  forward_ = glm::normalize(camera.forward);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  tan_half_y_ = std::tan(0.5f * camera.yfov);
  // The image's own aspect ratio wins over the file's: yfov is kept, as glTF intends.
  aspect_ = float(width) / float(height);
}

Ray PinholeCamera::generate(float px, float py) const {
  Ray ray;
  ray.origin = eye_;
  ray.direction = pinhole_direction(forward_, right_, up_, tan_half_y_, aspect_, float(width_), float(height_), px, py);
  return ray;
}

const Camera& select_camera(const Scene& scene, const std::string& name_or_index) {
  if (scene.cameras.empty()) throw Error(scene.source + ": the scene has no camera");
  int index = scene.find_camera(name_or_index);
  if (index >= 0) return scene.cameras[size_t(index)];
  std::string names;
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    names += (i ? ", " : "") + std::to_string(i) + " '" + scene.cameras[i].name + "'";
  throw Error("no camera '" + name_or_index + "' in " + scene.source + " (cameras: " + names + ")");
}

void resolve_resolution(const Camera& camera, int& width, int& height) {
  float aspect = camera.aspect > 0.0f ? camera.aspect : 1.0f;
  if (width < 0 || height < 0) throw Error("image size must be positive");
  if (width == 0 && height == 0) width = 640;
  // Clamped in double before the conversion: a huge size or a file's extreme aspect ratio would
  // overflow int (validate() then refuses the size with a message).
  auto side = [](double v) { return int(std::clamp(std::round(v), 1.0, double(INT_MAX))); };
  if (width == 0) width = side(double(height) * aspect);
  if (height == 0) height = side(double(width) / aspect);
}

glsl::ViewParams view_params(const PinholeCamera& camera, int width, int height, uint32_t seed) {
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

}  // namespace sst
