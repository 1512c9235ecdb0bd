// Sampling a triangle uniformly by the solid angle it subtends from a point (Arvo, "Stratified
// Sampling of Spherical Triangles", SIGGRAPH 1995; the formulation of pbrt-v4), shared C++/GLSL
// source. For an emitter close to the shading point this removes the 1/d^2 spike of area
// sampling, which otherwise makes fireflies where a light nearly touches a surface (the Cornell
// box's lamp, 1 cm below its ceiling). Cycles samples mesh lights the same way, so noise levels
// compare fairly. asin, atan2, sin and cos are core/math/accurate_math.h's: the spherical excess
// (angles summed, minus pi) amplifies any last-bit difference by pi / solid angle, and the mapping
// is ill-conditioned for u.x near 0 (k1 below cancels).
#ifndef SST_CORE_SAMPLING_SPHERICAL_TRIANGLE_H
#define SST_CORE_SAMPLING_SPHERICAL_TRIANGLE_H
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"

SST_BEGIN

// Solid angles in which spherical sampling is numerically safe and worth it (pbrt-v4's bounds).
SST_CONSTANT float kMinSphericalSolidAngle = 3e-4f;
SST_CONSTANT float kMaxSphericalSolidAngle = 6.22f;

// Angle between unit vectors without acos's loss of precision near 0 and pi.
SST_FUNC float spherical_angle_between(vec3 a, vec3 b) {
  if (dot3(a, b) < 0.0f) {
    SST_PRECISE vec3 s = a + b;
    SST_PRECISE float r = kPi - 2.0f * accurate_asin(min(1.0f, length3(s) / 2.0f));
    return r;
  }
  SST_PRECISE vec3 d = b - a;
  SST_PRECISE float r = 2.0f * accurate_asin(min(1.0f, length3(d) / 2.0f));
  return r;
}

SST_FUNC vec3 spherical_gram_schmidt(vec3 v, vec3 w) {
  SST_PRECISE vec3 r = v - dot3(v, w) * w;
  return r;
}

SST_FUNC float spherical_safe_sqrt(float x) { return sqrt(max(0.0f, x)); }

// Solid angle of triangle (v0, v1, v2) seen from p (Van Oosterom & Strackee 1983).
SST_FUNC float triangle_solid_angle(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  SST_PRECISE vec3 da = v0 - p, db = v1 - p, dc = v2 - p;
  vec3 a = normalize3(da), b = normalize3(db), c = normalize3(dc);
  float numerator = abs(dot3(a, cross3(b, c)));
  SST_PRECISE float denominator = 1.0f + dot3(a, b) + dot3(b, c) + dot3(c, a);
  SST_PRECISE float omega = 2.0f * accurate_atan2(numerator, denominator);
  return is_finite(omega) ? abs(omega) : 0.0f;
}

// Barycentrics (b1, b2) of the point hit by a direction drawn uniformly over the spherical
// triangle; `pdf` receives 1 / solid angle. Returns false for a degenerate spherical triangle
// (and then leaves `barycentric` unspecified).
SST_FUNC bool sample_spherical_triangle(vec3 p, vec3 v0, vec3 v1, vec3 v2, vec2 u, SST_OUT(vec2) barycentric, SST_OUT(float) pdf) {
  barycentric = vec2(0.0f);
  pdf = 0.0f;
  SST_PRECISE vec3 a = v0 - p, b = v1 - p, c = v2 - p;
  if (dot3(a, a) == 0.0f || dot3(b, b) == 0.0f || dot3(c, c) == 0.0f) return false;
  a = normalize3(a);
  b = normalize3(b);
  c = normalize3(c);
  // Normals of the great circles through each pair of vertices.
  vec3 n_ab = cross3(a, b), n_bc = cross3(b, c), n_ca = cross3(c, a);
  if (dot3(n_ab, n_ab) == 0.0f || dot3(n_bc, n_bc) == 0.0f || dot3(n_ca, n_ca) == 0.0f) return false;
  n_ab = normalize3(n_ab);
  n_bc = normalize3(n_bc);
  n_ca = normalize3(n_ca);
  // Interior angles; their excess over pi is the area (solid angle).
  float alpha = spherical_angle_between(n_ab, -n_ca), beta = spherical_angle_between(n_bc, -n_ab),
        gamma = spherical_angle_between(n_ca, -n_bc);
  SST_PRECISE float area_pi = alpha + beta + gamma;
  SST_PRECISE float area = area_pi - kPi;
  if (!(area > 0.0f)) return false;
  pdf = 1.0f / area;
  // Choose the sub-triangle of area u.x * area: find cos of the new vertex c' on arc (a, c).
  SST_PRECISE float ap_pi = kPi + u.x * (area_pi - kPi);
  float cos_alpha = accurate_cos(alpha), sin_alpha = accurate_sin(alpha);
  float sin_ap = accurate_sin(ap_pi), cos_ap = accurate_cos(ap_pi);
  SST_PRECISE float sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
  SST_PRECISE float cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
  SST_PRECISE float k1 = cos_phi + cos_alpha;
  SST_PRECISE float k2 = sin_phi - sin_alpha * dot3(a, b);
  SST_PRECISE float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
  cos_bp = clamp(is_finite(cos_bp) ? cos_bp : 1.0f, -1.0f, 1.0f);
  SST_PRECISE float sin_bp2 = 1.0f - cos_bp * cos_bp;
  float sin_bp = spherical_safe_sqrt(sin_bp2);
  SST_PRECISE vec3 cp = cos_bp * a + sin_bp * normalize3(spherical_gram_schmidt(c, a));
  // Then a direction on the arc from b to c' (uniform in area by u.y).
  SST_PRECISE float cos_theta = 1.0f - u.y * (1.0f - dot3(cp, b));
  SST_PRECISE float sin_theta2 = 1.0f - cos_theta * cos_theta;
  float sin_theta = spherical_safe_sqrt(sin_theta2);
  SST_PRECISE vec3 w = cos_theta * b + sin_theta * normalize3(spherical_gram_schmidt(cp, b));
  // Where the direction meets the triangle (Moller-Trumbore), as barycentrics of v1 and v2.
  SST_PRECISE vec3 e1 = v1 - v0, e2 = v2 - v0;
  vec3 s1 = cross3(w, e2);
  float divisor = dot3(s1, e1);
  if (divisor == 0.0f || !is_finite(divisor)) return false;
  SST_PRECISE vec3 s = p - v0;
  SST_PRECISE float b1 = dot3(s, s1) / divisor;
  SST_PRECISE float b2 = dot3(w, cross3(s, e1)) / divisor;
  b1 = clamp(is_finite(b1) ? b1 : 0.0f, 0.0f, 1.0f);
  b2 = clamp(is_finite(b2) ? b2 : 0.0f, 0.0f, 1.0f);
  if (b1 + b2 > 1.0f) {
    SST_PRECISE float sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  barycentric = vec2(b1, b2);
  return true;
}

SST_END

#endif  // SST_CORE_SAMPLING_SPHERICAL_TRIANGLE_H
