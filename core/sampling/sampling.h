// Warps from uniform random numbers to the distributions the renderers sample, with their pdfs.
#pragma once
#include "core/math/math.h"

namespace sst {

// Cosine-weighted direction about +z; pdf = cos(theta) / pi.
inline vec3 sample_cosine_hemisphere(float u1, float u2) {
  // Concentric mapping (Shirley & Chiu) keeps strata compact.
  float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f, 1.0f};
  float r, phi;
  if (a * a > b * b) {
    r = a;
    phi = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
  }
  float x = r * std::cos(phi), y = r * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y))};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
inline vec3 sample_uniform_sphere(float u1, float u2) {
  float z = 1.0f - 2.0f * u1;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform point on a triangle as barycentrics (b0, b1); b2 = 1 - b0 - b1. Heitz's low-distortion
// mapping would also do; the square-root warp is the classic, exact one.
inline vec2 sample_uniform_triangle(float u1, float u2) {
  float su = std::sqrt(u1);
  return {1.0f - su, u2 * su};
}

// Power heuristic with beta = 2 (Veach 1997).
inline float power_heuristic(float pdf_a, float pdf_b) {
  float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace sst
