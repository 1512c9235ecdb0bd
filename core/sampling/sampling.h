// Warps from uniform random numbers to the distributions the renderers sample, with their pdfs
// (shared C++/GLSL source). sin and cos are core/math/accurate_math.h's, so that both backends
// place the same directions.
#ifndef SST_CORE_SAMPLING_SAMPLING_H
#define SST_CORE_SAMPLING_SAMPLING_H
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"

SST_BEGIN

// Cosine-weighted direction about +z; pdf = cos(theta) / pi. The concentric mapping (Shirley &
// Chiu) keeps strata compact.
SST_FUNC vec3 sample_cosine_hemisphere(float u1, float u2) {
  SST_PRECISE float a = 2.0f * u1 - 1.0f;
  SST_PRECISE float b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) return vec3(0.0f, 0.0f, 1.0f);
  SST_PRECISE float r;
  SST_PRECISE float phi;
  if (a * a > b * b) {
    r = a;
    phi = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
  }
  SST_PRECISE float x = r * accurate_cos(phi);
  SST_PRECISE float y = r * accurate_sin(phi);
  SST_PRECISE float z2 = 1.0f - x * x - y * y;
  return vec3(x, y, sqrt(max(0.0f, z2)));
}

SST_FUNC float cosine_hemisphere_pdf(float cos_theta) { return max(cos_theta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere; pdf = kUniformSpherePdf.
SST_FUNC vec3 sample_uniform_sphere(float u1, float u2) {
  SST_PRECISE float z = 1.0f - 2.0f * u1;
  SST_PRECISE float r2 = 1.0f - z * z;
  float r = sqrt(max(0.0f, r2));
  SST_PRECISE float phi = 2.0f * kPi * u2;
  SST_PRECISE vec3 d = vec3(r * accurate_cos(phi), r * accurate_sin(phi), z);
  return d;
}
// 1 / (4 pi) rounded to float.
SST_CONSTANT float kUniformSpherePdf = 0.0795774715f;

// Uniform direction in the cone about +z whose half-angle theta_max has 1 - cos(theta_max) =
// `one_minus_cos`; pdf = 1 / (2 pi one_minus_cos). The cone is given by 1 - cos because a narrow
// one (a room seen from kilometres away) has a cos that float rounds to 1.
SST_FUNC vec3 sample_uniform_cone(float u1, float u2, float one_minus_cos) {
  SST_PRECISE float z = u1 * one_minus_cos;  // 1 - cos(theta)
  SST_PRECISE float s2 = z * (2.0f - z);
  float s = sqrt(max(0.0f, s2));
  SST_PRECISE float phi = 2.0f * kPi * u2;
  SST_PRECISE vec3 d = vec3(s * accurate_cos(phi), s * accurate_sin(phi), 1.0f - z);
  return d;
}

// Uniform point on a triangle as barycentrics (b0, b1); b2 = 1 - b0 - b1. Heitz's low-distortion
// mapping would also do; the square-root warp is the classic, exact one.
SST_FUNC vec2 sample_uniform_triangle(float u1, float u2) {
  float su = sqrt(u1);
  SST_PRECISE vec2 b = vec2(1.0f - su, u2 * su);
  return b;
}

// Power heuristic with beta = 2 (Veach 1997).
SST_FUNC float power_heuristic(float pdf_a, float pdf_b) {
  SST_PRECISE float a = pdf_a * pdf_a;
  SST_PRECISE float b = pdf_b * pdf_b;
  SST_PRECISE float w = a / (a + b);
  return a + b > 0.0f ? w : 0.0f;
}

SST_END

#endif  // SST_CORE_SAMPLING_SAMPLING_H
