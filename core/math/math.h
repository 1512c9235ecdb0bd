// Vector math for the whole tool's C++. glm is used because its types and functions have the GLSL
// names, so the C++ reads like the kernels shared with the Vulkan shaders (vector_math.h).
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math/vector_math.h"

namespace sst {
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::uvec3;
using glm::mat3;
using glm::mat4;
using glm::dvec3;

inline bool is_finite(vec3 v) { return is_finite3(v); }
inline float sqr(float x) { return x * x; }

struct Bounds3 {
  vec3 lo{kInf};
  vec3 hi{-kInf};
  void extend(vec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Bounds3& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  bool empty() const { return box_empty(lo, hi); }
  vec3 center() const { return box_center(lo, hi); }
  vec3 extent() const { return empty() ? vec3(0) : hi - lo; }
  float diagonal() const { return box_diagonal(lo, hi); }
};

}  // namespace sst
