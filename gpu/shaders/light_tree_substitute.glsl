// The SST substitute of a light-tree node from its two children, and the leaves: the GLSL twin of
// core/lighttree/substitute.cpp (make_leaf, make_padding_leaf, merge_children), in its operation
// order and `precise`, so that the GPU build reproduces the CPU's nodes bit for bit where the
// GPU's division and sqrt are correctly rounded (lavapipe). std::min/std::max and glm::min/max
// are spelled as their comparisons: GLSL's min/max may pick either zero of -0 and +0.
#ifndef SST_GPU_SHADERS_LIGHT_TREE_SUBSTITUTE_GLSL
#define SST_GPU_SHADERS_LIGHT_TREE_SUBSTITUTE_GLSL

#include "core/math/vector_math.h"

struct SubstituteThresholds {
  float v_min;
  float sigma_max_abs;  // sigma_max * D, scene units
};

uint substitute_suitability(float v, float sigma_z, SubstituteThresholds t) {
  return (v >= t.v_min && sigma_z <= t.sigma_max_abs) ? kLightNodeSuitable : 0u;
}

// glm::min / glm::max: (y < x) ? y : x and (x < y) ? y : x per component.
vec3 glm_min3(vec3 x, vec3 y) {
  return vec3(y.x < x.x ? y.x : x.x, y.y < x.y ? y.y : x.y, y.z < x.z ? y.z : x.z);
}
vec3 glm_max3(vec3 x, vec3 y) {
  return vec3(x.x < y.x ? y.x : x.x, x.y < y.y ? y.y : x.y, x.z < y.z ? y.z : x.z);
}

LightNode make_leaf(vec3 position, vec3 normal, vec3 intensity, uint vpl_index, SubstituteThresholds t) {
  LightNode leaf;
  leaf.bounds_lo = position;
  leaf.bounds_hi = position;
  leaf.left = vpl_index;
  leaf.right = kNoNode;
  leaf.intensity = intensity;
  leaf.vpl_count = 1u;
  leaf.mean = position;
  leaf.similarity = 1.0;
  precise float inv_length = 1.0 / sqrt(dot3(normal, normal));
  precise vec3 unit = normal * inv_length;
  leaf.normal = unit;
  leaf.sigma_z = 0.0;
  leaf.variance = vec3(0.0);
  leaf.flags = kLightNodeLeaf | substitute_suitability(1.0, 0.0, t);
  return leaf;
}

LightNode make_padding_leaf(SubstituteThresholds t) {
  LightNode leaf;
  leaf.bounds_lo = vec3(kInf);
  leaf.bounds_hi = vec3(-kInf);
  leaf.left = kNoNode;
  leaf.right = kNoNode;
  leaf.intensity = vec3(0.0);
  leaf.vpl_count = 0u;
  leaf.mean = vec3(0.0);
  leaf.similarity = 1.0;
  leaf.normal = vec3(0.0, 0.0, 1.0);
  leaf.sigma_z = 0.0;
  leaf.variance = vec3(0.0);
  leaf.flags = kLightNodeLeaf | substitute_suitability(1.0, 0.0, t);
  return leaf;
}

// substitute.cpp's merge_substitutes: with t = c2 / (c1 + c2), p = p1 + t delta and
// s2 = (1 - t) s2_1 + t s2_2 + t (1 - t) (R delta)*(R delta).
void merge_substitutes(inout LightNode parent, LightNode a, LightNode b) {
  float c1 = luminance(a.intensity), c2 = luminance(b.intensity);
  precise float total = c1 + c2;
  bool weighted = total > 0.0;
  precise float t = weighted ? c2 / total : 0.5;
  precise vec3 delta = b.mean - a.mean;
  precise vec3 mean = a.mean + t * delta;
  parent.mean = mean;
  precise vec3 normal_sum = (1.0 - t) * a.normal + t * b.normal;
  float len = sqrt(dot3(normal_sum, normal_sum));
  if (len > 1e-4) {
    precise float inv = 1.0 / len;
    precise vec3 n = normal_sum * inv;
    parent.normal = n;
  } else {
    parent.normal = c2 > c1 ? b.normal : a.normal;
  }
  vec3 local = to_local(basis_from_normal(parent.normal), delta);
  precise float spread = weighted ? t * (1.0 - t) : 0.0;
  if (weighted) {
    precise vec3 variance = (1.0 - t) * a.variance + t * b.variance + spread * (local * local);
    parent.variance = variance;
  } else {
    parent.variance = vec3(0.0);
  }
  float cosine = dot3(a.normal, b.normal);
  precise float similarity = a.similarity * b.similarity * (cosine < 0.0 ? 0.0 : cosine);
  parent.similarity = similarity;
  parent.sigma_z = sqrt(parent.variance.z);
}

void copy_substitute(inout LightNode to, LightNode from) {
  to.mean = from.mean;
  to.normal = from.normal;
  to.variance = from.variance;
  to.similarity = from.similarity;
  to.sigma_z = from.sigma_z;
}

LightNode merge_children(LightNode a, uint ia, LightNode b, uint ib, SubstituteThresholds t) {
  LightNode parent;
  parent.bounds_lo = glm_min3(a.bounds_lo, b.bounds_lo);
  parent.bounds_hi = glm_max3(a.bounds_hi, b.bounds_hi);
  parent.left = ia;
  parent.right = ib;
  precise vec3 intensity = a.intensity + b.intensity;
  parent.intensity = intensity;
  parent.vpl_count = a.vpl_count + b.vpl_count;
  if (a.vpl_count == 0u)
    copy_substitute(parent, b);  // b may be empty too: then parent is an empty node
  else if (b.vpl_count == 0u)
    copy_substitute(parent, a);
  else
    merge_substitutes(parent, a, b);
  parent.flags = substitute_suitability(parent.similarity, parent.sigma_z, t);
  return parent;
}

#endif
