// The GLSL twin of core/sampling/sampling.h: warps from uniform numbers to the distributions the
// renderers sample, in the C++'s operation order, with sin and cos within an ulp of glibc's
// (accurate_math.glsl): the GPU built-ins' larger errors moved VPLs and bounce rays measurably.
#ifndef SST_GPU_SHADERS_SAMPLING_GLSL
#define SST_GPU_SHADERS_SAMPLING_GLSL
#include "gpu/shaders/accurate_math.glsl"
#include "gpu/shaders/math.glsl"

// Cosine-weighted direction about +z (concentric mapping); pdf = cos(theta) / pi.
vec3 sample_cosine_hemisphere(float u1, float u2) {
  precise float a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
  if (a == 0.0 && b == 0.0) return vec3(0.0, 0.0, 1.0);
  precise float r, phi;
  if (a * a > b * b) {
    r = a;
    phi = (kPi / 4.0) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0) - (kPi / 4.0) * (a / b);
  }
  precise float x = r * accurate_cos(phi), y = r * accurate_sin(phi);
  precise float z2 = 1.0 - x * x - y * y;
  return vec3(x, y, sqrt(max(0.0, z2)));
}

float cosine_hemisphere_pdf(float cos_theta) { return max(cos_theta, 0.0) * kInvPi; }

// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
vec3 sample_uniform_sphere(float u1, float u2) {
  precise float z = 1.0 - 2.0 * u1;
  precise float r2 = 1.0 - z * z;
  float r = sqrt(max(0.0, r2));
  precise float phi = 2.0 * kPi * u2;
  precise vec3 d = vec3(r * accurate_cos(phi), r * accurate_sin(phi), z);
  return d;
}
// The float the C++ computes for 1 / (4 kPi), by its bits: a folded constant could round otherwise.
#define kUniformSpherePdf uintBitsToFloat(0x3DA2F983u)

// Uniform point on a triangle as barycentrics (b0, b1); b2 = 1 - b0 - b1.
vec2 sample_uniform_triangle(float u1, float u2) {
  float su = sqrt(u1);
  precise vec2 b = vec2(1.0 - su, u2 * su);
  return b;
}

// Power heuristic with beta = 2 (Veach 1997).
float power_heuristic(float pdf_a, float pdf_b) {
  precise float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  precise float w = a / (a + b);
  return a + b > 0.0 ? w : 0.0;
}

#endif
