// The GLSL twin of core/sampling/spherical_triangle.{h,cpp}: the solid angle of a triangle seen
// from a point, and uniform sampling of that solid angle (Arvo 1995, pbrt-v4's formulation), in
// the C++'s operation order and `precise`. asin, atan2, sin and cos are
// gpu/shaders/accurate_math.glsl's (within 1 ulp of glibc's; the built-ins are far coarser). The
// spherical excess (angles summed, minus pi) amplifies any last-bit difference by pi / solid
// angle, and the mapping is ill-conditioned for u.x near 0 (k1 below cancels), so a sample's pdf
// agrees with the CPU's to ~1e-5 relative and its point to a few times the CPU's own float error
// (tests/gpu/light_sampler_gpu_test.cpp), not to the ulp.
#ifndef SST_GPU_SHADERS_SPHERICAL_TRIANGLE_GLSL
#define SST_GPU_SHADERS_SPHERICAL_TRIANGLE_GLSL
#include "gpu/shaders/accurate_math.glsl"
#include "gpu/shaders/math.glsl"

// Solid angles in which spherical sampling is numerically safe and worth it (pbrt-v4's bounds).
const float kMinSphericalSolidAngle = 3e-4;
const float kMaxSphericalSolidAngle = 6.22;

// Angle between unit vectors without acos's loss of precision near 0 and pi.
float spherical_angle_between(vec3 a, vec3 b) {
  if (glm_dot(a, b) < 0.0) {
    precise vec3 s = a + b;
    precise float r = kPi - 2.0 * accurate_asin(min(1.0, glm_length(s) / 2.0));
    return r;
  }
  precise vec3 d = b - a;
  precise float r = 2.0 * accurate_asin(min(1.0, glm_length(d) / 2.0));
  return r;
}

vec3 spherical_gram_schmidt(vec3 v, vec3 w) {
  precise vec3 r = v - glm_dot(v, w) * w;
  return r;
}

float spherical_safe_sqrt(float x) { return sqrt(max(0.0, x)); }

// Solid angle of triangle (v0, v1, v2) seen from p (Van Oosterom & Strackee 1983).
float triangle_solid_angle(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  precise vec3 da = v0 - p, db = v1 - p, dc = v2 - p;
  vec3 a = glm_normalize(da), b = glm_normalize(db), c = glm_normalize(dc);
  float numerator = abs(glm_dot(a, glm_cross(b, c)));
  precise float denominator = 1.0 + glm_dot(a, b) + glm_dot(b, c) + glm_dot(c, a);
  precise float omega = 2.0 * accurate_atan2(numerator, denominator);
  return is_finite(omega) ? abs(omega) : 0.0;
}

// Barycentrics (b1, b2) of the point hit by a direction drawn uniformly over the spherical
// triangle; `pdf` receives 1 / solid angle. Returns false for a degenerate spherical triangle
// (and then leaves `barycentric` unspecified).
bool sample_spherical_triangle(vec3 p, vec3 v0, vec3 v1, vec3 v2, vec2 u, out vec2 barycentric, out float pdf) {
  barycentric = vec2(0.0);
  pdf = 0.0;
  precise vec3 a = v0 - p, b = v1 - p, c = v2 - p;
  if (glm_dot(a, a) == 0.0 || glm_dot(b, b) == 0.0 || glm_dot(c, c) == 0.0) return false;
  a = glm_normalize(a);
  b = glm_normalize(b);
  c = glm_normalize(c);
  // Normals of the great circles through each pair of vertices.
  vec3 n_ab = glm_cross(a, b), n_bc = glm_cross(b, c), n_ca = glm_cross(c, a);
  if (glm_dot(n_ab, n_ab) == 0.0 || glm_dot(n_bc, n_bc) == 0.0 || glm_dot(n_ca, n_ca) == 0.0) return false;
  n_ab = glm_normalize(n_ab);
  n_bc = glm_normalize(n_bc);
  n_ca = glm_normalize(n_ca);
  // Interior angles; their excess over pi is the area (solid angle).
  float alpha = spherical_angle_between(n_ab, -n_ca), beta = spherical_angle_between(n_bc, -n_ab),
        gamma = spherical_angle_between(n_ca, -n_bc);
  precise float area_pi = alpha + beta + gamma;
  precise float area = area_pi - kPi;
  if (!(area > 0.0)) return false;
  pdf = 1.0 / area;
  // Choose the sub-triangle of area u.x * area: find cos of the new vertex c' on arc (a, c).
  precise float ap_pi = kPi + u.x * (area_pi - kPi);
  float cos_alpha = accurate_cos(alpha), sin_alpha = accurate_sin(alpha);
  float sin_ap = accurate_sin(ap_pi), cos_ap = accurate_cos(ap_pi);
  precise float sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
  precise float cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
  precise float k1 = cos_phi + cos_alpha;
  precise float k2 = sin_phi - sin_alpha * glm_dot(a, b);
  precise float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
  cos_bp = clamp(is_finite(cos_bp) ? cos_bp : 1.0, -1.0, 1.0);
  precise float sin_bp2 = 1.0 - cos_bp * cos_bp;
  float sin_bp = spherical_safe_sqrt(sin_bp2);
  precise vec3 cp = cos_bp * a + sin_bp * glm_normalize(spherical_gram_schmidt(c, a));
  // Then a direction on the arc from b to c' (uniform in area by u.y).
  precise float cos_theta = 1.0 - u.y * (1.0 - glm_dot(cp, b));
  precise float sin_theta2 = 1.0 - cos_theta * cos_theta;
  float sin_theta = spherical_safe_sqrt(sin_theta2);
  precise vec3 w = cos_theta * b + sin_theta * glm_normalize(spherical_gram_schmidt(cp, b));
  // Where the direction meets the triangle (Moller-Trumbore), as barycentrics of v1 and v2.
  precise vec3 e1 = v1 - v0, e2 = v2 - v0;
  vec3 s1 = glm_cross(w, e2);
  float divisor = glm_dot(s1, e1);
  if (divisor == 0.0 || !is_finite(divisor)) return false;
  precise vec3 s = p - v0;
  precise float b1 = glm_dot(s, s1) / divisor;
  precise float b2 = glm_dot(w, glm_cross(s, e1)) / divisor;
  b1 = clamp(is_finite(b1) ? b1 : 0.0, 0.0, 1.0);
  b2 = clamp(is_finite(b2) ? b2 : 0.0, 0.0, 1.0);
  if (b1 + b2 > 1.0) {
    precise float sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  barycentric = vec2(b1, b2);
  return true;
}

#endif  // SST_GPU_SHADERS_SPHERICAL_TRIANGLE_GLSL
