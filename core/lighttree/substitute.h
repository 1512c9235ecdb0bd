// SST substitute distributions (Tatzgern et al. 2020, §3.2, eqs. 1-3; docs/design/methods.md), and
// the rest of a node that a bottom-up build derives from its two children (intensity, box, count).
//
// With weights c_i = luminance(I_i) of the two children:
//   p  = (c1 p1 + c2 p2) / (c1 + c2)                                              (eq. 1)
//   n  = normalize(c1 n1 + c2 n2)
//   s2 = (c1 (s2_1 + d1*d1) + c2 (s2_2 + d2*d2)) / (c1 + c2)                       (eq. 2)
//        d_i = to_local(basis_from_normal(n), p_i - p), '*' element-wise
//   v  = v1 v2 max(n1.n2, 0),  sigma_z = sqrt(s2.z)
//   suitable iff v >= v_min and sigma_z <= sigma_max_abs                           (eq. 3)
// computed in the rearranged, equivalent form of merge_substitutes below (t = c2 / (c1 + c2)).
//
// Children's variances. s2_i is the diagonal of child i's covariance in *its own* frame
// (basis_from_normal(n_i)); eq. 2 adds it to the parent's offsets unchanged, without rotating
// it into the parent's frame, and we follow the paper. The paper says so itself: "strongly
// diverging normals will alter the cluster coordinate system and thus partially invalidate the
// local variance values during merging", which is what v and sigma_z guard against. What this
// keeps exact, and the tests check: the mean p; the trace s2.x + s2.y + s2.z, which is the
// weighted mean squared distance from p whatever the frames (parallel-axis theorem); and every
// component when all normals of the subtree are equal (then all frames are the same). What it
// approximates: how that total splits over the three axes when normals differ. The tangent
// frame of basis_from_normal (Duff et al. 2017) jumps where n.z changes sign (walls), turning
// the tangent axes about n; that may swap s2.x and s2.y between children, never s2.z.
//
// Edge cases, handled here where they arise rather than patched over in the output:
// - Zero total weight, c1 + c2 = 0 (all VPLs black): p = midpoint of p1 and p2, s2 = 0,
//   n = normalize(n1 + n2).
// - Normals that cancel, |c1 n1 + c2 n2| <= 1e-4 (c1 + c2): n = the normal of the child with the
//   larger weight (the first child on a tie), never NaN. v is then ~0, so the node is unsuitable.
// - Empty children (perfect-tree padding, vpl_count 0) carry no distribution: a node with one
//   empty child copies the other child's substitute; a node with two is empty itself.
//
// Shared C++/GLSL source (core/math/cpu_gpu.h): both backends' builders build their nodes with
// these functions, so the GPU's trees equal the CPU's bit for bit wherever the GPU's division and
// sqrt are correctly rounded (lavapipe). Every rounding step is a SST_PRECISE temporary, and
// box unions use min3/max3 (glm's comparison order) rather than GLSL's min/max, which may pick
// either of -0 and +0.
#ifndef SST_CORE_LIGHTTREE_SUBSTITUTE_H
#define SST_CORE_LIGHTTREE_SUBSTITUTE_H
#include "core/lighttree/light_node.h"
#include "core/vpl/vpl.h"

SST_BEGIN

struct SubstituteThresholds {
  float v_min SST_DEFAULT(0.5f);
  float sigma_max_abs SST_DEFAULT(0.0f);  // in scene units: sigma_max * D
};

SST_FUNC uint substitute_suitability(float v, float sigma_z, SST_IN(SubstituteThresholds) t) {
  return (v >= t.v_min && sigma_z <= t.sigma_max_abs) ? kLightNodeSuitable : 0u;
}

// A leaf for VPL `vpl_index`: p = position, n = normalize(normal), s2 = 0, v = 1, sigma_z = 0.
SST_FUNC LightNode make_leaf(vec3 position, vec3 normal, vec3 intensity, uint vpl_index,
                             SST_IN(SubstituteThresholds) t) {
  LightNode leaf;
  leaf.bounds_lo = position;
  leaf.bounds_hi = position;
  leaf.left = vpl_index;
  leaf.right = kNoNode;
  leaf.intensity = intensity;
  leaf.vpl_count = 1u;
  leaf.mean = position;
  leaf.similarity = 1.0f;
  leaf.normal = normalize3(normal);
  leaf.sigma_z = 0.0f;
  leaf.variance = vec3(0.0f);
  leaf.flags = kLightNodeLeaf | substitute_suitability(1.0f, 0.0f, t);
  return leaf;
}

// A perfect tree's padding leaf: no VPL, zero intensity, empty box.
SST_FUNC LightNode make_padding_leaf(SST_IN(SubstituteThresholds) t) {
  LightNode leaf;
  leaf.bounds_lo = vec3(kInf);
  leaf.bounds_hi = vec3(-kInf);
  leaf.left = kNoNode;
  leaf.right = kNoNode;
  leaf.intensity = vec3(0.0f);
  leaf.vpl_count = 0u;
  leaf.mean = vec3(0.0f);
  leaf.similarity = 1.0f;
  leaf.normal = vec3(0.0f, 0.0f, 1.0f);
  leaf.sigma_z = 0.0f;
  leaf.variance = vec3(0.0f);
  leaf.flags = kLightNodeLeaf | substitute_suitability(1.0f, 0.0f, t);
  return leaf;
}

// The substitute of two non-empty children (formulas and edge cases at the top of this file).
// With t = c2 / (c1 + c2) and delta = p2 - p1, eq. 1 is p = p1 + t delta, the offsets are
// d1 = -t R delta and d2 = (1 - t) R delta (R: into the parent's frame), and eq. 2 becomes
//   s2 = (1 - t) s2_1 + t s2_2 + t (1 - t) (R delta)*(R delta),
// the same value with fewer operations and no cancellation in p_i - p. p stays between p1 and
// p2 in floating point and coincident children give exactly zero spread.
SST_FUNC void merge_substitutes(SST_INOUT(LightNode) parent, SST_IN(LightNode) a, SST_IN(LightNode) b) {
  float c1 = luminance(a.intensity);
  float c2 = luminance(b.intensity);
  SST_PRECISE float total = c1 + c2;
  bool weighted = total > 0.0f;
  // Zero total weight: the midpoint, the unweighted normal, no spread.
  SST_PRECISE float t = weighted ? c2 / total : 0.5f;
  SST_PRECISE vec3 delta = b.mean - a.mean;
  SST_PRECISE vec3 mean = a.mean + t * delta;
  parent.mean = mean;
  SST_PRECISE vec3 normal_sum = (1.0f - t) * a.normal + t * b.normal;
  float len = length3(normal_sum);
  if (len > 1e-4f) {
    // One division instead of three: this merge is the build's hot loop.
    SST_PRECISE float inv = 1.0f / len;
    SST_PRECISE vec3 n = normal_sum * inv;
    parent.normal = n;
  } else {
    parent.normal = c2 > c1 ? b.normal : a.normal;
  }
  vec3 local = to_local(basis_from_normal(parent.normal), delta);
  SST_PRECISE float spread = weighted ? t * (1.0f - t) : 0.0f;
  if (weighted) {
    SST_PRECISE vec3 variance = (1.0f - t) * a.variance + t * b.variance + spread * (local * local);
    parent.variance = variance;
  } else {
    parent.variance = vec3(0.0f);
  }
  float cosine = dot3(a.normal, b.normal);
  SST_PRECISE float similarity = a.similarity * b.similarity * (cosine < 0.0f ? 0.0f : cosine);
  parent.similarity = similarity;
  parent.sigma_z = sqrt(parent.variance.z);
}

SST_FUNC void copy_substitute(SST_INOUT(LightNode) to, SST_IN(LightNode) from) {
  to.mean = from.mean;
  to.normal = from.normal;
  to.variance = from.variance;
  to.similarity = from.similarity;
  to.sigma_z = from.sigma_z;
}

// The node whose children are a (node index ia) and b (node index ib).
SST_FUNC LightNode merge_children(SST_IN(LightNode) a, uint ia, SST_IN(LightNode) b, uint ib,
                                  SST_IN(SubstituteThresholds) t) {
  LightNode parent;
  parent.bounds_lo = min3(a.bounds_lo, b.bounds_lo);
  parent.bounds_hi = max3(a.bounds_hi, b.bounds_hi);
  parent.left = ia;
  parent.right = ib;
  SST_PRECISE vec3 intensity = a.intensity + b.intensity;
  parent.intensity = intensity;
  parent.vpl_count = a.vpl_count + b.vpl_count;
  if (light_node_empty(a))
    copy_substitute(parent, b);  // b may be empty too: then parent is an empty node
  else if (light_node_empty(b))
    copy_substitute(parent, a);
  else
    merge_substitutes(parent, a, b);
  parent.flags = substitute_suitability(parent.similarity, parent.sigma_z, t);
  return parent;
}

SST_END

#ifdef __cplusplus
namespace sst {
// A leaf for a C++ Vpl.
inline LightNode make_leaf(const Vpl& vpl, uint vpl_index, const SubstituteThresholds& t) {
  return make_leaf(vpl.position, vpl.normal, vpl.intensity, vpl_index, t);
}
}  // namespace sst
#endif

#endif  // SST_CORE_LIGHTTREE_SUBSTITUTE_H
