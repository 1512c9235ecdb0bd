// The hybrid thesis's geometric similarity test S(x, y) (eq. 5.3; shared C++/GLSL source): two
// surface points are similar when their normals are closer than n_min in cosine and the points
// nearer than d_max. `hybrid` blends the cuts of similar blocks only; the joint bilateral
// upsampler (core/filter) takes low-resolution texels from similar points only (thesis ch. 6).
// Each caller measures the distance its own way (world-space points, or depths along the view).
#ifndef SST_CORE_MATH_GEOMETRIC_SIMILARITY_H
#define SST_CORE_MATH_GEOMETRIC_SIMILARITY_H
#include "core/math/vector_math.h"

SST_BEGIN

SST_FUNC bool geometrically_similar(vec3 nx, vec3 ny, float distance, float n_min, float d_max) {
  return dot3(nx, ny) > n_min && distance < d_max;
}

SST_END

#endif  // SST_CORE_MATH_GEOMETRIC_SIMILARITY_H
