#include "core/lighttree/substitute.h"

namespace sst {
namespace {

uint32_t suitability(float v, float sigma_z, const SubstituteThresholds& t) {
  return (v >= t.v_min && sigma_z <= t.sigma_max_abs) ? LightNode::kSuitable : 0u;
}

void copy_substitute(LightNode& to, const LightNode& from) {
  to.mean = from.mean;
  to.normal = from.normal;
  to.variance = from.variance;
  to.similarity = from.similarity;
  to.sigma_z = from.sigma_z;
}

// The substitute of two non-empty children (see substitute.h for the formulas and edge cases).
// With t = c2 / (c1 + c2) and delta = p2 - p1, eq. 1 is p = p1 + t delta, the offsets are
// d1 = -t R delta and d2 = (1 - t) R delta (R: into the parent's frame), and eq. 2 becomes
//   s2 = (1 - t) s2_1 + t s2_2 + t (1 - t) (R delta)*(R delta),
// the same value with fewer operations and no cancellation in p_i - p. p stays between p1 and
// p2 in floating point and coincident children give exactly zero spread.
void merge_substitutes(LightNode& parent, const LightNode& a, const LightNode& b) {
  float c1 = luminance(a.intensity), c2 = luminance(b.intensity);
  float total = c1 + c2;
  bool weighted = total > 0.0f;
  // Zero total weight: the midpoint, the unweighted normal, no spread.
  float t = weighted ? c2 / total : 0.5f;
  vec3 delta = b.mean - a.mean;
  parent.mean = a.mean + t * delta;
  vec3 normal_sum = (1.0f - t) * a.normal + t * b.normal;
  float length = std::sqrt(glm::dot(normal_sum, normal_sum));
  // One division instead of glm's three: this merge is the build's hot loop.
  parent.normal = length > 1e-4f ? normal_sum * (1.0f / length) : (c2 > c1 ? b.normal : a.normal);
  vec3 local = to_local(basis_from_normal(parent.normal), delta);
  float spread = weighted ? t * (1.0f - t) : 0.0f;
  parent.variance = weighted ? (1.0f - t) * a.variance + t * b.variance + spread * (local * local) : vec3(0.0f);
  parent.similarity = a.similarity * b.similarity * std::max(glm::dot(a.normal, b.normal), 0.0f);
  parent.sigma_z = std::sqrt(parent.variance.z);
}

}  // namespace

LightNode make_leaf(const Vpl& vpl, uint32_t vpl_index, const SubstituteThresholds& thresholds) {
  LightNode leaf;
  leaf.bounds_lo = vpl.position;
  leaf.bounds_hi = vpl.position;
  leaf.left = vpl_index;
  leaf.right = kNoNode;
  leaf.intensity = vpl.intensity;
  leaf.vpl_count = 1;
  leaf.mean = vpl.position;
  leaf.similarity = 1.0f;
  leaf.normal = vpl.normal * (1.0f / std::sqrt(glm::dot(vpl.normal, vpl.normal)));
  leaf.sigma_z = 0.0f;
  leaf.variance = vec3(0.0f);
  leaf.flags = LightNode::kLeaf | suitability(1.0f, 0.0f, thresholds);
  return leaf;
}

LightNode make_padding_leaf(const SubstituteThresholds& thresholds) {
  LightNode leaf;
  leaf.bounds_lo = vec3(kInf);
  leaf.bounds_hi = vec3(-kInf);
  leaf.left = kNoNode;
  leaf.right = kNoNode;
  leaf.intensity = vec3(0.0f);
  leaf.vpl_count = 0;
  leaf.mean = vec3(0.0f);
  leaf.similarity = 1.0f;
  leaf.normal = vec3(0.0f, 0.0f, 1.0f);
  leaf.sigma_z = 0.0f;
  leaf.variance = vec3(0.0f);
  leaf.flags = LightNode::kLeaf | suitability(1.0f, 0.0f, thresholds);
  return leaf;
}

void merge_children(LightNode& parent, const LightNode& a, uint32_t ia, const LightNode& b, uint32_t ib,
                    const SubstituteThresholds& thresholds) {
  parent.bounds_lo = glm::min(a.bounds_lo, b.bounds_lo);
  parent.bounds_hi = glm::max(a.bounds_hi, b.bounds_hi);
  parent.left = ia;
  parent.right = ib;
  parent.intensity = a.intensity + b.intensity;
  parent.vpl_count = a.vpl_count + b.vpl_count;
  if (a.empty())
    copy_substitute(parent, b);  // b may be empty too: then parent is an empty node
  else if (b.empty())
    copy_substitute(parent, a);
  else
    merge_substitutes(parent, a, b);
  parent.flags = suitability(parent.similarity, parent.sigma_z, thresholds);
}

}  // namespace sst
