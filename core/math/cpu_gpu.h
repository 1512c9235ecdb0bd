// The common subset of C++ (glm) and GLSL 4.50 in which every algorithm that runs on both backends
// is written once: the CPU compiles the file as C++ inside namespace sst, the Vulkan shaders
// #include the same file (glslc -I <source root>). This header is the only place where the two
// languages differ; a shared file includes it first.
//
// Rules of the subset (what the shared files may use):
// - Functions: SST_FUNC before each definition; parameters spelled SST_IN(T) / SST_INOUT(T) /
//   SST_OUT(T) for structs and anything written (plain by-value scalars and vectors need nothing).
//   No recursion, no function pointers or std::function, no containers, no member functions, no
//   default arguments, no references other than through the macros.
// - Structs are plain (no constructors); build them member by member and return them. A member may
//   carry SST_DEFAULT(value): its default in C++ (GLSL has none), so that C++ objects start defined.
// - Types: float, int, uint, bool, vecN, uvecN, ivecN; float literals carry an f suffix and uint
//   literals a u, so that C++ never computes in double. No swizzles (sst builds glm with
//   GLM_FORCE_XYZW_ONLY); v.x or v[i].
// - lanes4: four floats operated on lane by lane, for one scalar computation run four times side
//   by side (GLSL: vec4; C++: one SIMD register, which glm's vec4 does not compile to). Only what
//   is defined below: lanes4(a, b, c, d), l[i] (read), +, -, * (by lanes4 or a float), /, min,
//   max, sqrt, each lane rounding as the scalar operation would.
// - Built-ins with GLSL's names: abs, min, max, clamp, sqrt, floor, dot, cross, length, normalize,
//   floatBitsToUint, uintBitsToFloat, bitfieldReverse, findMSB, isnan, isinf, exp, pow (glm and
//   <cmath> provide most of them in C++). exp and pow are the drivers' own, so a kernel using them
//   agrees across backends to a few ulps, not to the bit (the filters, core/filter, need no more).
// - Arithmetic whose bits matter is written into SST_PRECISE temporaries: GLSL's `precise`
//   forbids the driver to fuse a*b+c; C++ is built with -ffp-contract=off for the same reason.
// - Constants at file scope: SST_CONSTANT float kName = 1.0f;
// - SST_BEGIN / SST_END around the file's definitions (namespace sst in C++).
#ifndef SST_CORE_MATH_CPU_GPU_H
#define SST_CORE_MATH_CPU_GPU_H

#ifdef __cplusplus
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace sst {
using uint = uint32_t;
using glm::bvec2;
using glm::ivec2;
using glm::ivec3;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

using glm::abs;
using glm::clamp;
using glm::floatBitsToUint;
using glm::floor;
using glm::max;
using glm::min;
using glm::uintBitsToFloat;
using std::exp;
using std::pow;
using std::sqrt;
// GLSL's abs: +0 for -0, and no branch (glm's scalar abs is x >= 0 ? x : -x, a branch that random
// signs mispredict).
inline float abs(float x) { return std::fabs(x); }
inline vec2 abs(vec2 v) { return vec2(std::fabs(v.x), std::fabs(v.y)); }
inline vec3 abs(vec3 v) { return vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)); }
inline vec4 abs(vec4 v) { return vec4(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z), std::fabs(v.w)); }
inline bool isnan(float x) { return std::isnan(x); }
inline bool isinf(float x) { return std::isinf(x); }
// GLSL's bitfieldReverse for one 32-bit word (glm's generic version loops over bit widths).
inline uint bitfieldReverse(uint x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}
// GLSL's findMSB of an unsigned word: the index of its highest set bit, -1 for 0.
inline int findMSB(uint x) { return x == 0u ? -1 : 31 - std::countl_zero(x); }

// GCC's vector extension: operators act lane by lane, as SSE instructions. min and max keep
// glm's (and so the scalar code's) choice between equal values and between -0 and +0.
struct lanes4 {
  using Register = float __attribute__((vector_size(16)));
  Register v;
  lanes4() = default;
  explicit lanes4(Register r) : v(r) {}
  lanes4(float a, float b, float c, float d) : v(Register{a, b, c, d}) {}
  float operator[](int i) const { return v[i]; }
};
inline lanes4 operator+(lanes4 a, lanes4 b) { return lanes4(a.v + b.v); }
inline lanes4 operator-(lanes4 a, lanes4 b) { return lanes4(a.v - b.v); }
inline lanes4 operator*(lanes4 a, lanes4 b) { return lanes4(a.v * b.v); }
inline lanes4 operator*(float s, lanes4 a) { return lanes4(s * a.v); }
inline lanes4 operator*(lanes4 a, float s) { return lanes4(a.v * s); }
inline lanes4 operator/(lanes4 a, lanes4 b) { return lanes4(a.v / b.v); }
inline lanes4 sqrt(lanes4 a) {
#if defined(__SSE__)
  return lanes4(__builtin_ia32_sqrtps(a.v));
#else
  return lanes4(std::sqrt(a.v[0]), std::sqrt(a.v[1]), std::sqrt(a.v[2]), std::sqrt(a.v[3]));
#endif
}
inline lanes4 min(lanes4 x, lanes4 y) { return lanes4(y.v < x.v ? y.v : x.v); }  // glm::min
inline lanes4 max(lanes4 x, lanes4 y) { return lanes4(x.v < y.v ? y.v : x.v); }  // glm::max
}  // namespace sst

#define SST_BEGIN namespace sst {
#define SST_END }
#define SST_FUNC inline
#define SST_IN(T) const T&
#define SST_INOUT(T) T&
#define SST_OUT(T) T&
#define SST_PRECISE
#define SST_CONSTANT inline constexpr
#define SST_DEFAULT(value) = value

#else  // GLSL

#define SST_BEGIN
#define SST_END
#define SST_FUNC
#define lanes4 vec4
#define SST_IN(T) in T
#define SST_INOUT(T) inout T
#define SST_OUT(T) out T
#define SST_PRECISE precise
#define SST_CONSTANT const
#define SST_DEFAULT(value)

#endif

#endif  // SST_CORE_MATH_CPU_GPU_H
