// A ray's hit turned into what shading needs: position, normals facing the viewer, material
// values with textures applied, and the emitted radiance toward the viewer.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/material/brdf.h"
#include "core/scene/scene.h"

namespace sst {

struct Surface {
  vec3 p{0.0f};
  vec3 ng{0.0f};  // geometric normal, flipped to the side the ray came from
  vec3 ns{0.0f};  // interpolated shading normal, on the same side as ng
  vec2 uv{0.0f};
  uint32_t triangle = 0;
  uint32_t material = 0;
  bool front_face = true;  // the ray hit the side the triangle's winding faces
  vec3 base_color{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  vec3 emission{0.0f};  // radiance leaving toward the viewer (0 from the back of one-sided)
};

// `incoming` is the ray direction that hit the surface.
Surface make_surface(const Scene& scene, const Hit& hit, vec3 incoming);
// Emitted radiance of triangle `tri` at barycentrics (b1, b2), seen from the side `front_face`.
vec3 triangle_emission(const Scene& scene, uint32_t tri, vec2 barycentric, bool front_face);
vec3 triangle_geometric_normal(const Scene& scene, uint32_t tri);  // unit, by winding
float triangle_area(const Scene& scene, uint32_t tri);

}  // namespace sst
