// A virtual point light (instant radiosity, Keller 1997; docs/design/methods.md): a point on a
// diffuse surface that re-emits the light it received, with a cosine lobe about its normal. It
// emits intensity * max(0, n . w) in direction w (W/sr per RGB channel). Shared C++/GLSL source.
#ifndef SST_CORE_VPL_VPL_H
#define SST_CORE_VPL_VPL_H
#include "core/math/vector_math.h"

SST_BEGIN

struct Vpl {
  vec3 position SST_DEFAULT(vec3(0.0f));
  vec3 normal SST_DEFAULT(vec3(0.0f, 0.0f, 1.0f));  // unit, on the side the light arrived from
  vec3 intensity SST_DEFAULT(vec3(0.0f));           // throughput * albedo / pi
};

SST_END

#ifdef __cplusplus
#include <vector>
namespace sst {
using VplSet = std::vector<Vpl>;
}  // namespace sst
#endif

#endif  // SST_CORE_VPL_VPL_H
