// `sst`: stochastic substitute trees (Tatzgern et al. 2020, §4; docs/design/methods.md). Biased by design.
// The estimate is sst_estimate.h's (both backends); this is the method and its parameters.
//
// Per indirect sample:
// 1. Lobe. A BRDF with a specular lobe picks the glossy lobe with probability
//    brdf_specular_probability(brdf, wo) (the path tracer's choice: Fresnel-weighted luminance of F0
//    against the diffuse albedo's luminance, clamped to [0.1, 0.9]; 1 for a pure metal), else
//    the diffuse lobe; a diffuse-only BRDF always takes the diffuse lobe. The paper chooses "by
//    the magnitude of the material terms" without a formula; this is one. Each lobe shades with
//    its own part of the BRDF (diffuse + specular = the BRDF, brdf.h) divided by the lobe's
//    probability, so the two lobes together estimate the whole BRDF.
// 2. Walk from the root, child i with probability w_i / (w_1 + w_2), w = M * G * I:
//    I = lum(node intensity); G = 1 / max(d^2, eps^2), d = distance from x to the node's box,
//    eps = distance_floor * D (the tree's length scale) (paper §4.1: a lower bound on the distance
//    instead of SLC's inside-the-box rule, which loses colour bleeding from close VPLs);
//    M = BRDF bound times the cosine bound over the box: diffuse lum(albedo)/pi; glossy the
//    specular BRDF toward the box point closest to the mirror direction R (R itself when the
//    ray x + tR hits the box; paper §4.1), plus a small floor so that no box above the surface
//    gets weight 0 (which would drop its VPLs' highlights altogether). V = 1. A dead branch
//    (w_1 + w_2 = 0) wastes the sample.
// 3. Stop. Diffuse: at the first node flagged suitable (LightNode::suitable(): normal similarity
//    v >= v_min and sigma_z <= sigma_max * D, light_tree.h) or a leaf. Glossy: at a leaf only
//    (substitutes would blur highlights).
// 4. Shade. A leaf: its VPL. A suitable internal node: a position drawn from the node's Gaussian
//    (three normal deviates scaled by sqrt(variance.x), sqrt(variance.y), sigma_z in the frame
//    basis_from_normal(normal) about the mean), clamped into the node's box, shaded through
//    shade_vpl as Vpl{position, node normal, node summed intensity}. Divided by the walk's
//    probability and the lobe's.
//
// Parameters: those of TreeMethodParams (tree_method_params.h) and SstParams below. v_min and
// sigma_max of LightTreeParams set which nodes are suitable (smaller v_min, larger sigma_max:
// earlier stops, fewer nodes visited, more bias). With substitutes = false no internal node is
// a stop, and sst is an unbiased (w.r.t. exhaustive) light-tree sampler with the weights above
// (LightTreeParams caps v_min at 1, which does not exclude internal nodes of equal normals).
#pragma once
#include "core/manylight/slc/slc_sampler.h"
#include "core/manylight/sst/sst_estimate.h"

namespace sst {

struct SstParams {
  bool substitutes = true;
  // The paper gives no value for its epsilon. Measured on the Cornell box (4096 VPLs, 16 spp,
  // 128x128, indirect RMSE vs exhaustive): 0.01 -> 0.28, 0.05 -> 0.062, 0.1 -> 0.048,
  // 0.2 -> 0.053, 0.5 -> 0.062 (slc: 0.062). Small floors let a box containing x outweigh its
  // sibling by (d / eps)^2 whatever its VPLs contribute, which starves distant bright clusters.
  float distance_floor = 0.1f;
  template <class V>
  void visit(V&& v) {
    v("substitutes", substitutes,
      "stop the diffuse walk at a suitable node (v_min, sigma_max) and sample its Gaussian substitute; false: walk to "
      "a leaf (unbiased)");
    v("distance_floor", distance_floor,
      "lower bound eps of the distance in the traversal weights (the paper's epsilon), as a fraction of the "
      "tree's D (see sigma_max_relative_to); the paper gives no value, the default measured best on the Cornell box");
  }
};

struct SstMethodParams {
  TreeMethodParams tree_method{kNodeFloorAboveForSst};
  SstParams sst;
  template <class V>
  void visit(V&& v) {
    tree_method.visit(v);
    sst.visit(v);
  }
};

// Throws sst::Error for an impossible value (naming the parameter).
void validate(const SstParams& p);

enum class SstLobe { diffuse, glossy };

// The weights of step 2 (sst_child_weights, sst_estimate.h) at `point`, whose brdf is the lobe's
// part of the BRDF (sst_lobe_brdf); eps as above; floor_fraction: LightTreeParams::
// node_distance_floor. For exact stop probabilities in tests.
ChildWeights sst_weights(const ShadingPoint& point, float eps, SstLobe lobe, float floor_fraction = 0.0f);
// The stop rule of step 3 (leaves only for the glossy lobe or without substitutes).
StopRule sst_stop_rule(SstLobe lobe, bool substitutes = true);

class SstSampler final : public TreeSamplerBase {
 public:
  SstSampler(LightTreeParams params, SstParams sst) : TreeSamplerBase(std::move(params)), sst_(sst) {}
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_sst(inputs(), point, sampler);
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_sst; }
  void build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) override;

 private:
  SstParams sst_;
};

}  // namespace sst
