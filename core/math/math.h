// Vector math for the whole tool. glm is used because its types and functions have the GLSL
// names, so code shared with the Vulkan shaders (RNG, structures) reads the same on both sides.
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sst {
using glm::vec2;
using glm::vec3;
using glm::vec4;
using glm::uvec3;
using glm::mat3;
using glm::mat4;
using glm::dvec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInf = std::numeric_limits<float>::infinity();

// Rec. 709 luminance: the scalar weight of an RGB intensity everywhere in the tool.
inline float luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
inline float max_component(vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
inline bool is_finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline float sqr(float x) { return x * x; }

struct Bounds3 {
  vec3 lo{kInf};
  vec3 hi{-kInf};
  void extend(vec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Bounds3& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  vec3 center() const { return 0.5f * (lo + hi); }
  vec3 extent() const { return empty() ? vec3(0) : hi - lo; }
  float diagonal() const { return glm::length(extent()); }
};

// Orthonormal basis around n (Duff et al. 2017, branchless and robust for any unit n).
struct Frame {
  vec3 t, b, n;
  static Frame from_normal(vec3 n) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float bb = n.x * n.y * a;
    return {vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x),
            vec3(bb, sign + n.y * n.y * a, -n.y), n};
  }
  vec3 to_local(vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  vec3 to_world(vec3 v) const { return v.x * t + v.y * b + v.z * n; }
};
}  // namespace sst
