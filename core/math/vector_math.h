// Constants and vector helpers of every shared kernel (core/math/cpu_gpu.h), the orthonormal basis
// around a normal, and axis-aligned boxes. dot3 / cross3 / length3 / normalize3 compute in glm's
// operation order and `precise`, so that a kernel calling them gives the same bits on both
// backends; GLSL's built-ins would evaluate in the driver's order.
#ifndef SST_CORE_MATH_VECTOR_MATH_H
#define SST_CORE_MATH_VECTOR_MATH_H
#include "core/math/cpu_gpu.h"

#ifdef __cplusplus
#include <limits>
namespace sst {
inline constexpr float kInf = std::numeric_limits<float>::infinity();
}
#else
#define kInf uintBitsToFloat(0x7F800000u)
#endif

SST_BEGIN

SST_CONSTANT float kPi = 3.14159265358979323846f;
SST_CONSTANT float kInvPi = 0.31830988618379067154f;
// The largest float below 1: where a uniform number in [0, 1) is clamped.
SST_CONSTANT float kOneMinusEpsilon = 0.99999994f;

SST_FUNC float dot3(vec3 a, vec3 b) {
  SST_PRECISE float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

SST_FUNC vec3 cross3(vec3 x, vec3 y) {
  SST_PRECISE vec3 r = vec3(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
  return r;
}

SST_FUNC float length3(vec3 v) { return sqrt(dot3(v, v)); }

// glm::normalize: v * inversesqrt(dot(v, v)), glm's inversesqrt being 1 / sqrt.
SST_FUNC vec3 normalize3(vec3 v) {
  SST_PRECISE float inv = 1.0f / sqrt(dot3(v, v));
  SST_PRECISE vec3 r = v * inv;
  return r;
}

// glm::reflect(i, n) = i - n * dot(n, i) * 2.
SST_FUNC vec3 reflect3(vec3 i, vec3 n) {
  SST_PRECISE vec3 r = i - n * dot3(n, i) * 2.0f;
  return r;
}

// Rec. 709 luminance: the scalar weight of an RGB intensity everywhere in the tool.
SST_FUNC float luminance(vec3 c) {
  SST_PRECISE float r = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
  return r;
}

// Component-wise minimum and maximum as glm computes them, (y < x) ? y : x and (x < y) ? y : x:
// GLSL's min/max may return either of -0 and +0 when they compare equal.
SST_FUNC vec3 min3(vec3 x, vec3 y) {
  return vec3(y.x < x.x ? y.x : x.x, y.y < x.y ? y.y : x.y, y.z < x.z ? y.z : x.z);
}
SST_FUNC vec3 max3(vec3 x, vec3 y) {
  return vec3(x.x < y.x ? y.x : x.x, x.y < y.y ? y.y : x.y, x.z < y.z ? y.z : x.z);
}

SST_FUNC float max_component(vec3 v) { return max(v.x, max(v.y, v.z)); }

SST_FUNC bool is_finite(float x) { return !isinf(x) && !isnan(x); }
SST_FUNC bool is_finite3(vec3 v) { return is_finite(v.x) && is_finite(v.y) && is_finite(v.z); }

SST_FUNC float sign_bit_set(float x) { return (floatBitsToUint(x) & 0x80000000u) != 0u ? 1.0f : 0.0f; }

// Orthonormal basis around a unit normal n (Duff et al. 2017, branchless, robust for any n):
// the shading basis of a surface point and the local axes of an SST substitute.
struct Basis {
  vec3 t;
  vec3 b;
  vec3 n;
};

SST_FUNC Basis basis_from_normal(vec3 n) {
  // copysign(1, n.z): the sign bit decides, so -0.0 gives -1.
  float sign = sign_bit_set(n.z) != 0.0f ? -1.0f : 1.0f;
  SST_PRECISE float a = -1.0f / (sign + n.z);
  SST_PRECISE float bb = n.x * n.y * a;
  SST_PRECISE vec3 t = vec3(1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x);
  SST_PRECISE vec3 b = vec3(bb, sign + n.y * n.y * a, -n.y);
  Basis f;
  f.t = t;
  f.b = b;
  f.n = n;
  return f;
}

SST_FUNC vec3 to_local(SST_IN(Basis) f, vec3 v) { return vec3(dot3(v, f.t), dot3(v, f.b), dot3(v, f.n)); }

SST_FUNC vec3 to_world(SST_IN(Basis) f, vec3 v) {
  SST_PRECISE vec3 r = v.x * f.t + v.y * f.b + v.z * f.n;
  return r;
}

// An axis-aligned box [lo, hi] as two corners, the form both backends store boxes in. The C++
// Bounds3 (math.h) answers with these functions, so the CPU and the GPU measure a box alike.

// lo > hi on some axis: an empty box (a padding leaf's box is lo = +inf, hi = -inf).
SST_FUNC bool box_empty(vec3 lo, vec3 hi) { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }

SST_FUNC bool box_inside(vec3 lo, vec3 hi, vec3 x) {
  return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
}

SST_FUNC vec3 box_center(vec3 lo, vec3 hi) {
  SST_PRECISE vec3 c = 0.5f * (lo + hi);
  return c;
}

// The squared length of the box's diagonal (0 for an empty box), for comparisons without a root.
SST_FUNC float box_diagonal2(vec3 lo, vec3 hi) {
  SST_PRECISE vec3 e = hi - lo;
  return box_empty(lo, hi) ? 0.0f : dot3(e, e);
}

// Length of the box's diagonal (0 for an empty box): length3's bits, sqrt(dot3).
SST_FUNC float box_diagonal(vec3 lo, vec3 hi) { return sqrt(box_diagonal2(lo, hi)); }

SST_END

#ifdef __cplusplus
#include "core/math/math.h"  // the C++-only rest (Bounds3, ...), for C++ includers of shared kernels
#endif

#endif  // SST_CORE_MATH_VECTOR_MATH_H
