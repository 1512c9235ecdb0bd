#include "core/render/centre_gbuffer.h"

#include <tbb/parallel_for.h>

#include "core/render/pinhole.h"
#include "core/render/reprojection.h"
#include "core/shading/surface.h"

namespace sst {

CentreGBuffer centre_gbuffer(const EmbreeAccel& accel, const Scene& scene, const std::vector<vec3>& previous_positions,
                             const glsl::ViewParams& view, const glsl::ViewParams& previous_view) {
  const int width = int(view.width), height = int(view.height);
  CentreGBuffer out{Image(width, height, 1), Image(width, height, 3), Image(width, height, 2), Image(width, height, 1)};
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      vec3 dir = camera_direction(view, centre.x, centre.y);
      BvhHit hit = accel_intersect(accel, view.eye, dir);
      vec2 previous(0.0f);
      float distance = 0.0f;
      bool seen;
      if (hit.triangle == BVH_INVALID_TRIANGLE) {
        seen = project_direction_to_pixel(previous_view, dir, previous);
      } else {
        Surface s = make_surface(scene, hit.triangle, vec2(hit.u, hit.v), dir);
        out.depth.at(x, y, 0) = hit.t;
        out.normal.set_rgb(x, y, s.ns);
        uvec3 tri = scene.triangles[hit.triangle];
        float w = 1.0f - hit.u - hit.v;
        vec3 p = w * previous_positions[tri.x] + hit.u * previous_positions[tri.y] + hit.v * previous_positions[tri.z];
        seen = project_to_pixel(previous_view, p, previous, distance);
        if (!seen) distance = 0.0f;
      }
      vec2 motion = seen ? previous - centre : vec2(0.0f);
      out.motion.at(x, y, 0) = motion.x;
      out.motion.at(x, y, 1) = motion.y;
      out.previous_depth.at(x, y, 0) = distance;
    }
  });
  return out;
}

}  // namespace sst
