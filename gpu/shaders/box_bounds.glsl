// The GLSL twin of core/lighttree/box_bounds.{h,cpp}: bounds of a light-tree node's box
// [lo, hi] seen from a shading point x, the building blocks of every tree sampler's weights.
// Same operation order as the C++, `precise` (no fma), so that decisions taken on these values
// (which child, whether a box is behind the surface) are the CPU's except at float ties.
#ifndef SST_GPU_SHADERS_BOX_BOUNDS_GLSL
#define SST_GPU_SHADERS_BOX_BOUNDS_GLSL
#include "gpu/shaders/math.glsl"

// Bounds3::empty: lo > hi on some axis (a padding leaf's box is lo = +inf, hi = -inf).
bool box_empty(vec3 lo, vec3 hi) { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }

bool box_inside(vec3 lo, vec3 hi, vec3 x) {
  return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
}

// Bounds3::center and Bounds3::diagonal.
vec3 box_center(vec3 lo, vec3 hi) {
  precise vec3 c = 0.5 * (lo + hi);
  return c;
}

float box_diagonal(vec3 lo, vec3 hi) {
  precise vec3 e = hi - lo;
  return box_empty(lo, hi) ? 0.0 : glm_length(e);
}

// Squared distance from x to the box (0 inside; +inf for an empty box).
float box_distance2_min(vec3 lo, vec3 hi, vec3 x) {
  if (box_empty(lo, hi)) return kInf;
  precise vec3 below = lo - x, above = x - hi;
  vec3 d = max(max(below, above), vec3(0.0));
  return glm_dot(d, d);
}

// Squared distance from x to the farthest point of the box.
float box_distance2_max(vec3 lo, vec3 hi, vec3 x) {
  precise vec3 a = lo - x, b = hi - x;
  vec3 d = max(abs(a), abs(b));
  return glm_dot(d, d);
}

// Smallest |t| over [lo, hi]: 0 when the interval straddles 0.
float box_min_abs(float lo, float hi) { return lo <= 0.0 && hi >= 0.0 ? 0.0 : min(abs(lo), abs(hi)); }

// Walter 2005's bound of max(0, n . normalize(y - x)) over the box (slc, sst).
float box_cos_bound(vec3 lo, vec3 hi, vec3 x, vec3 n) {
  if (box_empty(lo, hi)) return 0.0;
  if (box_inside(lo, hi, x)) return 1.0;
  Frame f = frame_from_normal(n);
  vec3 llo = vec3(kInf), lhi = vec3(-kInf);
  for (int c = 0; c < 8; ++c) {
    vec3 corner = vec3((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y, (c & 4) != 0 ? hi.z : lo.z);
    precise vec3 d = corner - x;
    vec3 l = frame_to_local(f, d);
    llo = min(llo, l);
    lhi = max(lhi, l);
  }
  if (!(lhi.z > 0.0)) return 0.0;  // wholly below the tangent plane
  float dx = box_min_abs(llo.x, lhi.x), dy = box_min_abs(llo.y, lhi.y);
  precise float len2 = dx * dx + dy * dy + lhi.z * lhi.z;
  return len2 > 0.0 ? min(1.0, lhi.z / sqrt(len2)) : 1.0;
}

// min(1, max_y n.(y - x) / dmin): the cheap bound of rtslc's weights and cuts.
float box_cos_bound_linear(vec3 lo, vec3 hi, vec3 x, vec3 n) {
  float d2 = box_distance2_min(lo, hi, x);
  if (!(d2 > 0.0)) return 1.0;  // x in the box: every direction may occur
  precise vec3 l = lo - x, h = hi - x;
  precise vec3 nl = n * l, nh = n * h;
  precise float zmax = max(nl.x, nh.x) + max(nl.y, nh.y) + max(nl.z, nh.z);
  if (!(zmax > 0.0)) return 0.0;
  return min(1.0, zmax / sqrt(d2));
}

#endif
