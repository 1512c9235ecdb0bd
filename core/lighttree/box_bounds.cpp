#include "core/lighttree/box_bounds.h"

namespace sst {
namespace {
bool inside(const Bounds3& b, vec3 x) {
  return x.x >= b.lo.x && x.x <= b.hi.x && x.y >= b.lo.y && x.y <= b.hi.y && x.z >= b.lo.z && x.z <= b.hi.z;
}

// Smallest |t| over [lo, hi]: 0 when the interval straddles 0.
float min_abs(float lo, float hi) { return lo <= 0.0f && hi >= 0.0f ? 0.0f : std::min(std::abs(lo), std::abs(hi)); }
}  // namespace

float box_distance2_min(const Bounds3& box, vec3 x) {
  if (box.empty()) return kInf;
  vec3 d = glm::max(glm::max(box.lo - x, x - box.hi), vec3(0.0f));
  return glm::dot(d, d);
}

float box_distance2_max(const Bounds3& box, vec3 x) {
  vec3 d = glm::max(glm::abs(box.lo - x), glm::abs(box.hi - x));
  return glm::dot(d, d);
}

float box_cos_bound(const Bounds3& box, vec3 x, vec3 n) {
  if (box.empty()) return 0.0f;
  if (inside(box, x)) return 1.0f;
  Frame f = Frame::from_normal(n);
  vec3 lo(kInf), hi(-kInf);
  for (int c = 0; c < 8; ++c) {
    vec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z);
    vec3 l = f.to_local(corner - x);
    lo = glm::min(lo, l);
    hi = glm::max(hi, l);
  }
  if (!(hi.z > 0.0f)) return 0.0f;  // wholly below the tangent plane
  float dx = min_abs(lo.x, hi.x), dy = min_abs(lo.y, hi.y);
  float len2 = dx * dx + dy * dy + hi.z * hi.z;
  return len2 > 0.0f ? std::min(1.0f, hi.z / std::sqrt(len2)) : 1.0f;
}

float box_cos_bound_linear(const Bounds3& box, vec3 x, vec3 n) {
  float d2 = box_distance2_min(box, x);
  if (!(d2 > 0.0f)) return 1.0f;  // x in the box: every direction may occur
  vec3 lo = box.lo - x, hi = box.hi - x;
  // max over the box of n . (y - x): per axis the larger of the two ends.
  float zmax = std::max(n.x * lo.x, n.x * hi.x) + std::max(n.y * lo.y, n.y * hi.y) + std::max(n.z * lo.z, n.z * hi.z);
  if (!(zmax > 0.0f)) return 0.0f;
  return std::min(1.0f, zmax / std::sqrt(d2));
}

}  // namespace sst
