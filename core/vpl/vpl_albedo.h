// The albedo with which a surface point re-emits the light a VPL stands for (shared C++/GLSL
// source): instant radiosity's light paths (core/vpl/light_path.h) and BRSM's pVPLs
// (core/brsm/brsm.h) alike. The includer provides Surface (core/shading/surface.h).
#ifndef SST_CORE_VPL_VPL_ALBEDO_H
#define SST_CORE_VPL_VPL_ALBEDO_H
#include "core/math/vector_math.h"

SST_BEGIN

// The albedo a VPL reflects with: the diffuse lobe's (all of the base colour when diffuse_only).
SST_FUNC vec3 vpl_albedo(SST_IN(Surface) s, bool diffuse_only) {
  SST_PRECISE vec3 a = (1.0f - s.metallic) * s.base_color;
  return diffuse_only ? s.base_color : a;
}

SST_END

#endif  // SST_CORE_VPL_VPL_ALBEDO_H
