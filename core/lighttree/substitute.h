// SST substitute distributions (Tatzgern et al. 2020, §3.2, eqs. 1-3; METHODS.md §2), and the
// rest of a node that a bottom-up build derives from its two children (intensity, box, count).
//
// With weights c_i = luminance(I_i) of the two children:
//   p  = (c1 p1 + c2 p2) / (c1 + c2)                                              (eq. 1)
//   n  = normalize(c1 n1 + c2 n2)
//   s2 = (c1 (s2_1 + d1*d1) + c2 (s2_2 + d2*d2)) / (c1 + c2)                       (eq. 2)
//        d_i = to_local(basis_from_normal(n), p_i - p), '*' element-wise
//   v  = v1 v2 max(n1.n2, 0),  sigma_z = sqrt(s2.z)
//   suitable iff v >= v_min and sigma_z <= sigma_max_abs                           (eq. 3)
// computed in the rearranged, equivalent form of substitute.cpp (t = c2 / (c1 + c2)).
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
// Edge cases (DESIGN.md: handled where they arise):
// - Zero total weight, c1 + c2 = 0 (all VPLs black): p = midpoint of p1 and p2, s2 = 0,
//   n = normalize(n1 + n2).
// - Normals that cancel, |c1 n1 + c2 n2| <= 1e-4 (c1 + c2): n = the normal of the child with the
//   larger weight (the first child on a tie), never NaN. v is then ~0, so the node is unsuitable.
// - Empty children (perfect-tree padding, vpl_count 0) carry no distribution: a node with one
//   empty child copies the other child's substitute; a node with two is empty itself.
#pragma once
#include "core/lighttree/light_tree.h"

namespace sst {

struct SubstituteThresholds {
  float v_min = 0.5f;
  float sigma_max_abs = 0.0f;  // in scene units: sigma_max * D
};

// A leaf for VPL `vpl_index`: p = position, n = normalize(normal), s2 = 0, v = 1, sigma_z = 0.
LightNode make_leaf(const Vpl& vpl, uint32_t vpl_index, const SubstituteThresholds& thresholds);
// A perfect tree's padding leaf: no VPL, zero intensity, empty box.
LightNode make_padding_leaf(const SubstituteThresholds& thresholds);
// Writes node `parent` from its children a (node index ia) and b (node index ib).
void merge_children(LightNode& parent, const LightNode& a, uint32_t ia, const LightNode& b, uint32_t ib,
                    const SubstituteThresholds& thresholds);

}  // namespace sst
