#include "core/sampling/spherical_triangle.h"

namespace sst {
namespace {

// Angle between unit vectors without acos's loss of precision near 0 and pi.
float angle_between(vec3 a, vec3 b) {
  if (glm::dot(a, b) < 0.0f) return kPi - 2.0f * std::asin(std::min(1.0f, glm::length(a + b) / 2.0f));
  return 2.0f * std::asin(std::min(1.0f, glm::length(b - a) / 2.0f));
}

vec3 gram_schmidt(vec3 v, vec3 w) { return v - glm::dot(v, w) * w; }

float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

}  // namespace

float triangle_solid_angle(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  vec3 a = glm::normalize(v0 - p), b = glm::normalize(v1 - p), c = glm::normalize(v2 - p);
  float numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  float denominator = 1.0f + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
  float omega = 2.0f * std::atan2(numerator, denominator);
  return std::isfinite(omega) ? std::abs(omega) : 0.0f;
}

bool sample_spherical_triangle(vec3 p, vec3 v0, vec3 v1, vec3 v2, vec2 u, vec2* barycentric, float* pdf) {
  vec3 a = v0 - p, b = v1 - p, c = v2 - p;
  if (glm::dot(a, a) == 0.0f || glm::dot(b, b) == 0.0f || glm::dot(c, c) == 0.0f) return false;
  a = glm::normalize(a);
  b = glm::normalize(b);
  c = glm::normalize(c);
  // Normals of the great circles through each pair of vertices.
  vec3 n_ab = glm::cross(a, b), n_bc = glm::cross(b, c), n_ca = glm::cross(c, a);
  if (glm::dot(n_ab, n_ab) == 0.0f || glm::dot(n_bc, n_bc) == 0.0f || glm::dot(n_ca, n_ca) == 0.0f) return false;
  n_ab = glm::normalize(n_ab);
  n_bc = glm::normalize(n_bc);
  n_ca = glm::normalize(n_ca);
  // Interior angles; their excess over pi is the area (solid angle).
  float alpha = angle_between(n_ab, -n_ca), beta = angle_between(n_bc, -n_ab), gamma = angle_between(n_ca, -n_bc);
  float area_pi = alpha + beta + gamma;
  float area = area_pi - kPi;
  if (!(area > 0.0f)) return false;
  *pdf = 1.0f / area;
  // Choose the sub-triangle of area u.x * area: find cos of the new vertex c' on arc (a, c).
  float ap_pi = kPi + u.x * (area_pi - kPi);
  float cos_alpha = std::cos(alpha), sin_alpha = std::sin(alpha);
  float sin_phi = std::sin(ap_pi) * cos_alpha - std::cos(ap_pi) * sin_alpha;
  float cos_phi = std::cos(ap_pi) * cos_alpha + std::sin(ap_pi) * sin_alpha;
  float k1 = cos_phi + cos_alpha;
  float k2 = sin_phi - sin_alpha * glm::dot(a, b);
  float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
  cos_bp = std::clamp(std::isfinite(cos_bp) ? cos_bp : 1.0f, -1.0f, 1.0f);
  float sin_bp = safe_sqrt(1.0f - cos_bp * cos_bp);
  vec3 cp = cos_bp * a + sin_bp * glm::normalize(gram_schmidt(c, a));
  // Then a direction on the arc from b to c' (uniform in area by u.y).
  float cos_theta = 1.0f - u.y * (1.0f - glm::dot(cp, b));
  float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  vec3 w = cos_theta * b + sin_theta * glm::normalize(gram_schmidt(cp, b));
  // Where the direction meets the triangle (Moller-Trumbore), as barycentrics of v1 and v2.
  vec3 e1 = v1 - v0, e2 = v2 - v0;
  vec3 s1 = glm::cross(w, e2);
  float divisor = glm::dot(s1, e1);
  if (divisor == 0.0f || !std::isfinite(divisor)) return false;
  vec3 s = p - v0;
  float b1 = glm::dot(s, s1) / divisor;
  float b2 = glm::dot(w, glm::cross(s, e1)) / divisor;
  b1 = std::clamp(std::isfinite(b1) ? b1 : 0.0f, 0.0f, 1.0f);
  b2 = std::clamp(std::isfinite(b2) ? b2 : 0.0f, 0.0f, 1.0f);
  if (b1 + b2 > 1.0f) {
    float sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  *barycentric = {b1, b2};
  return true;
}

}  // namespace sst
