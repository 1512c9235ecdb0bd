// A camera ray's first hit made ready to shade by a VPL method's estimator, one text for both
// backends (common C++/GLSL subset): many_light_method.cpp on the CPU, many_light.comp on the GPU.
// GLSL includes it after its scene hooks (gpu/shaders/surface.glsl), C++ through surface.h's.
#ifndef SST_CORE_MANYLIGHT_SHADING_POINT_H
#define SST_CORE_MANYLIGHT_SHADING_POINT_H
#include "core/manylight/estimator.h"
#ifdef __cplusplus
#include "core/shading/surface.h"
#else
#include "core/shading/surface_eval.h"
#endif

SST_BEGIN

// The hit `s`, `depth` from the camera, of a ray along `ray_direction` (any length) through pixel (x, y).
SST_FUNC ShadingPoint shading_point(SST_IN(Surface) s, vec3 ray_direction, float depth, bool diffuse_only, int x,
                                   int y) {
  ShadingPoint sp;
  sp.p = s.p;
  sp.ng = s.ng;
  sp.offset = s.offset;
  sp.lift = s.lift;
  sp.basis = basis_from_normal(s.ns);
  sp.wo = to_local(sp.basis, -normalize3(ray_direction));
  sp.brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
  sp.x = x;
  sp.y = y;
  sp.depth = depth;
  return sp;
}

SST_END
#endif
