// What every indirect estimator (core/manylight/<name>/<name>_estimate.h) shares, written once
// for both backends (shared C++/GLSL source): the shading point, the estimate, one VPL shaded
// with visibility, and the walk probability of the tree samplers.
//
// A kernel reads the sampler's inputs (many_light_layout.h) only through these hooks; C++ defines
// them in sampler_inputs.h, a shader before including this file (gpu/shaders/indirect_sampler.glsl):
//   ML_CTX_PARAM, ML_CTX       the leading parameter and argument of every kernel function that
//                              reads the inputs (C++: `const SamplerInputs& ml,`; GLSL: empty)
//   ML_PARAMS                  the SamplerParams
//   ML_NODE(i)                 LightNode i of the tree
//   ML_VPL(j)                  Vpl j
//   ML_CUT_NODE(i), ML_CUT_SIZE(b), ML_CUT_GUIDE(b), ML_MOCK_CUT(j)   the per-block cuts
//   ML_OCCLUDED(x, ng, p, n)   whether the shadow ray from x (geometric normal ng, on the VPL's
//                              side) to a VPL at p with normal n is blocked
//   ML_COUNT_ITERATION()       once per iteration of a loop over VPLs (lavapipe's loop budget)
#ifndef SST_CORE_MANYLIGHT_ESTIMATOR_H
#define SST_CORE_MANYLIGHT_ESTIMATOR_H
#include "core/lighttree/light_node.h"
#include "core/manylight/many_light_layout.h"
#include "core/material/brdf.h"
#include "core/math/box_bounds.h"
#include "core/rng/sobol_sampler.h"
#include "core/vpl/vpl_shading.h"
#ifdef __cplusplus
#include "core/manylight/sampler_inputs.h"
#endif

SST_BEGIN

// A camera ray's first hit, ready to shade.
struct ShadingPoint {
  vec3 p SST_DEFAULT(vec3(0.0f));
  vec3 ng SST_DEFAULT(vec3(0.0f));  // geometric normal on the viewer's side
  float offset SST_DEFAULT(0.0f);   // how far rays leaving p are lifted along ng (Surface::offset)
  vec3 lift SST_DEFAULT(vec3(0.0f));  // the shadow-terminator lift of direct light (Surface::lift)
  Basis basis;                      // shading basis (basis.n = shading normal)
  vec3 wo SST_DEFAULT(vec3(0.0f));  // toward the viewer, in the shading basis
  Brdf brdf;
  int x SST_DEFAULT(0);  // pixel
  int y SST_DEFAULT(0);
  float depth SST_DEFAULT(0.0f);  // distance from the camera (PathSample::depth)
};

struct IndirectEstimate {
  vec3 value SST_DEFAULT(vec3(0.0f));  // an estimate of sum_j contribution_j * visibility_j
  uint nodes_visited SST_DEFAULT(0u);  // tree nodes visited to draw the sample(s)
  uint shadow_rays SST_DEFAULT(0u);
};

SST_FUNC IndirectEstimate indirect_estimate_zero() {
  IndirectEstimate e;
  e.value = vec3(0.0f);
  e.nodes_visited = 0u;
  e.shadow_rays = 0u;
  return e;
}

// The singularity clamp distance at sp (vpl_clamp_at).
SST_FUNC float ml_clamp_distance(ML_CTX_PARAM SST_IN(ShadingPoint) sp) {
  return vpl_clamp_at(ML_PARAMS.clamp_distance, ML_PARAMS.clamp_per_depth, sp.depth);
}

// Whether a suitable node may stand in for its VPLs at sp (sst, hybrid): only where its box looks
// small from sp, its diagonal at most substitute_max_extent times the distance from sp to the box
// (0: wherever the node is suitable, the papers' rule). The papers' tests (normals, spread along
// the normal) say nothing of a node's width: a coplanar ground kilometres wide is one suitable
// node whose Gaussian, fitted to VPLs crowded near the view, puts its samples where they are not.
SST_FUNC bool ml_substitute_allowed(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_IN(LightNode) node) {
  float ratio = ML_PARAMS.substitute_max_extent;
  if (!(ratio > 0.0f)) return true;
  SST_PRECISE vec3 extent = node.bounds_hi - node.bounds_lo;
  SST_PRECISE float width2 = dot3(extent, extent);
  SST_PRECISE float bound2 = ratio * ratio * box_distance2_min(node.bounds_lo, node.bounds_hi, sp.p);
  return width2 <= bound2;
}

// One VPL's contribution at sp, with visibility: the shadow ray is traced (and counted) only when
// the unshadowed contribution is non-zero.
SST_FUNC vec3 shade_vpl(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_IN(Vpl) vpl, SST_INOUT(uint) shadow_rays) {
  vec3 c = vpl_contribution(vpl, sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, ml_clamp_distance(ML_CTX sp));
  if (max_component(c) <= 0.0f) return vec3(0.0f);
  shadow_rays += 1u;
  if (ML_OCCLUDED(sp.p, sp.ng, vpl.position, vpl.normal)) return vec3(0.0f);
  return c;
}

// The probability of a walk down a light tree, a product of up to tree-height factors, as a float
// mantissa m and a power-of-two exponent e (m renormalised whenever it falls below 2^-64), so that
// it never underflows: c / P stays finite wherever its true value is.
struct TreeProbability {
  float m;
  int e;
};

SST_FUNC TreeProbability tree_probability(float m) {
  TreeProbability p;
  p.m = m;
  p.e = 0;
  return p;
}

SST_FUNC TreeProbability tree_probability_times(TreeProbability p, float factor) {
  SST_PRECISE float m = p.m * factor;
  p.m = m;
  if (p.m > 0.0f && p.m < 5.42101086e-20f) {  // 2^-64
    p.m = ldexp(p.m, 64);                     // exact
    p.e -= 64;
  }
  return p;
}

// c / P; 0 for P <= 0, c <= 0, or a result outside float's range (never a NaN in the image).
SST_FUNC vec3 divide_by_probability(vec3 c, TreeProbability p) {
  if (!(p.m > 0.0f) || max_component(c) <= 0.0f) return vec3(0.0f);
  SST_PRECISE vec3 q = c / p.m;
  // ldexp saturates to +inf (overflow) or 0 (underflow).
  vec3 v = vec3(ldexp(q.x, -p.e), ldexp(q.y, -p.e), ldexp(q.z, -p.e));
  return is_finite3(v) ? v : vec3(0.0f);
}

// A walk from the root down a light tree: one tree_walk_step per internal node, the node's child
// weights computed by the method.
//
// One uniform serves several steps, as in pbrt-v4's light BVH: a step that goes left with
// probability p keeps u < p as the fresh uniform u / p, and u >= p as (u - p) / (1 - p), rather
// than drawing a Sobol point (three hashes, two scrambles) at each of a walk's 15-20 choices.
// Each rescale spends bits of u, though: a uniform whose choices since its draw had probability
// P is a multiple of about 2^-24 / P, and a child of probability q is then taken with a
// probability off by up to that much. So a step draws afresh where 2^-24 / P would exceed q / 256
// for the less likely child q: every choice's probabilities are right to 1/256 of the smaller
// one (or to 2^-24, a fresh uniform's own grain), while the estimate divides by the exact ones.
// In the breakfast room 11% (slc) and 13% (sst) of the choices draw. The first choices of a walk
// share one Sobol dimension, which stratifies a pixel's samples over the top subtrees jointly.
SST_CONSTANT float kTreeWalkUniformBits = 1.52587891e-05f;  // 2^-16 = 2^-24 x 256

struct TreeWalk {
  uint node;  // where the walk is; kNoNode: a dead branch
  TreeProbability probability;
  uint nodes_visited;  // nodes whose weights were evaluated, the stop node included
  float u;             // the uniform for the next choice
  float u_span;        // P: the probability of the choices u has made since it was drawn
};

SST_FUNC TreeWalk tree_walk_begin(uint root) {
  TreeWalk w;
  w.node = root;
  w.probability = tree_probability(root == kNoNode ? 0.0f : 1.0f);
  w.nodes_visited = 0u;
  w.u = 0.0f;
  w.u_span = 0.0f;  // spent: the first choice draws
  return w;
}

// At internal node `node` with child weights w: child i with probability w_i / (w_0 + w_1). A child
// of weight 0 is never taken, and no uniform is used unless both can be. A dead branch (a zero or
// non-finite sum) ends the walk with node = kNoNode: the sample is wasted.
SST_FUNC void tree_walk_step(SST_INOUT(TreeWalk) walk, SST_IN(LightNode) node, vec2 w, SST_INOUT(PixelSampler) ps) {
  float sum = w.x + w.y;
  if (!(sum > 0.0f) || !is_finite(sum)) {
    walk.node = kNoNode;
    walk.probability = tree_probability(0.0f);
    return;
  }
  float p_left = w.x / sum;
  float p_right = w.y / sum;
  bool left = w.y <= 0.0f;
  if (w.x > 0.0f && w.y > 0.0f) {
    if (walk.u_span * min(p_left, p_right) < kTreeWalkUniformBits) {
      walk.u = pixel_sampler_get1d(ps);
      walk.u_span = 1.0f;
    }
    left = walk.u < p_left;
    walk.u = left ? remap_below(walk.u, p_left) : remap_above(walk.u, p_left);
    SST_PRECISE float span = walk.u_span * (left ? p_left : p_right);
    walk.u_span = span;
  }
  walk.probability = tree_probability_times(walk.probability, left ? p_left : p_right);
  walk.node = left ? node.left : node.right;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_ESTIMATOR_H
