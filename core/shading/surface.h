// A ray's hit turned into what shading needs: position, normals facing the viewer, material
// values with textures applied, and the emitted radiance toward the viewer. The computation is
// core/shading/surface_eval.h, shared with the GPU, reading the Scene through
// core/scene/scene_access.h: make_surface, triangle_emission, triangle_geometric_normal and
// triangle_area take the Scene as their first argument.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/material/brdf.h"
#include "core/scene/scene.h"
#include "core/scene/scene_access.h"
#include "core/shading/surface_eval.h"

namespace sst {

// `incoming` is the ray direction that hit the surface.
inline Surface make_surface(const Scene& scene, const Hit& hit, vec3 incoming) {
  return make_surface(scene, hit.triangle, hit.barycentric, incoming);
}

}  // namespace sst
