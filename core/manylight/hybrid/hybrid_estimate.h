// `hybrid`, shallow light cuts over a stochastic substitute tree (the hybrid thesis, ch. 5), the
// estimate at one shading point (shared C++/GLSL source; hybrid_sampler.h is the method). The
// pixel blends the cuts of its four nearest blocks (built at the block centres) index by index:
// for cut index i one of the four similar blocks is drawn by bilinear weight, and the pixel walks
// from that cut's node i with expected-contribution weights to a leaf or a suitable node (a point
// light drawn from its Gaussian); with no similar block it walks from every node of the mock cut.
// Float throughout, as the thesis's GPU code.
#ifndef SST_CORE_MANYLIGHT_HYBRID_HYBRID_ESTIMATE_H
#define SST_CORE_MANYLIGHT_HYBRID_HYBRID_ESTIMATE_H
#include "core/math/box_bounds.h"
#include "core/math/accurate_math.h"
#include "core/math/geometric_similarity.h"
#include "core/manylight/estimator.h"

SST_BEGIN

// lum(I) G_avg / max(d^2, c^2), G_avg the mean over the box corners of max(n . normalize(corner -
// x), 0): a node's expected contribution, the walk's weight and the cuts' error. d is floored at
// floor_fraction times the box's diagonal (LightTreeParams::node_distance_floor; the walks only:
// a cut should split the wide node that holds its pivot first).
SST_FUNC float hybrid_weight(SST_IN(LightNode) node, vec3 x, vec3 n, float clamp_distance, float floor_fraction) {
  if (light_node_empty(node)) return 0.0f;
  float g = 0.0f;
  for (int c = 0; c < 8; ++c) {
    vec3 corner = vec3((c & 1) != 0 ? node.bounds_hi.x : node.bounds_lo.x,
                       (c & 2) != 0 ? node.bounds_hi.y : node.bounds_lo.y,
                       (c & 4) != 0 ? node.bounds_hi.z : node.bounds_lo.z);
    SST_PRECISE vec3 d = corner - x;
    float len = length3(d);
    SST_PRECISE float cosine = dot3(n, d) / len;
    if (len > 0.0f) g += max(cosine, 0.0f);
  }
  SST_PRECISE float c2 = clamp_distance * clamp_distance;
  float d2 = max(box_distance2_floored(node.bounds_lo, node.bounds_hi, x, floor_fraction), c2);
  SST_PRECISE float w = luminance(node.intensity) * (g * 0.125f) / d2;
  return is_finite(w) ? w : 0.0f;
}

// Two standard normal deviates (Box-Muller).
SST_FUNC vec2 hybrid_normal_pair(SST_INOUT(PixelSampler) ps) {
  vec2 u = pixel_sampler_get2d(ps);
  float r = sqrt(-2.0f * accurate_log(1.0f - u.x));  // u.x < 1: finite
  SST_PRECISE float phi = 2.0f * kPi * u.y;
  SST_PRECISE vec2 v = vec2(r * accurate_cos(phi), r * accurate_sin(phi));
  return v;
}

// A point light drawn from a suitable node's substitute distribution (as SST): the mean plus
// normal deviates scaled by the standard deviations in the node's basis, clamped into its box,
// carrying the node's summed intensity and normal.
SST_FUNC Vpl hybrid_sample_substitute(SST_IN(LightNode) node, SST_INOUT(PixelSampler) ps) {
  vec2 a = hybrid_normal_pair(ps);
  vec2 b = hybrid_normal_pair(ps);
  vec3 sd = sqrt(max(node.variance, vec3(0.0f)));
  SST_PRECISE vec3 scaled = vec3(a.x, a.y, b.x) * sd;
  vec3 offset = to_world(basis_from_normal(node.normal), scaled);
  SST_PRECISE vec3 p = node.mean + offset;
  Vpl v;
  v.position = clamp(p, node.bounds_lo, node.bounds_hi);
  v.normal = node.normal;
  v.intensity = node.intensity;
  return v;
}

// One walk from cut node `from`, adding to e.
SST_FUNC void hybrid_traverse(ML_CTX_PARAM SST_IN(ShadingPoint) sp, uint from, SST_INOUT(PixelSampler) ps,
                              SST_INOUT(IndirectEstimate) e) {
  uint i = from;
  float prob = 1.0f;
  float clamp_distance = ml_clamp_distance(ML_CTX sp);
  for (uint step = 0u; step < ML_PARAMS.tree_node_count; ++step) {  // bound: a malformed tree
    e.nodes_visited += 1u;
    LightNode node = ML_NODE(i);
    if (light_node_empty(node)) return;
    if (light_node_is_leaf(node) || (light_node_suitable(node) && ml_substitute_allowed(ML_CTX sp, node))) {
      // A suitable node is close enough to a flat patch: its substitute stands for its VPLs.
      Vpl v = light_node_is_leaf(node) ? ML_VPL(node.left) : hybrid_sample_substitute(node, ps);
      vec3 c = shade_vpl(ML_CTX sp, v, e.shadow_rays);
      e.value += c / prob;
      return;
    }
    float w0 = hybrid_weight(ML_NODE(node.left), sp.p, sp.basis.n, clamp_distance, ML_PARAMS.node_distance_floor);
    float w1 = hybrid_weight(ML_NODE(node.right), sp.p, sp.basis.n, clamp_distance, ML_PARAMS.node_distance_floor);
    SST_PRECISE float w = w0 + w1;
    if (!(w > 0.0f)) return;  // neither child is expected to contribute: no backtracking
    float p0 = w0 / w;
    bool left = pixel_sampler_get1d(ps) < p0;
    prob *= left ? p0 : 1.0f - p0;
    i = left ? node.left : node.right;
  }
}

SST_FUNC IndirectEstimate estimate_hybrid(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  IndirectEstimate e = indirect_estimate_zero();
  if (ML_PARAMS.tree_root == kNoNode) return e;
  // The four block centres around the pixel and their bilinear weights (clamped at the border,
  // where a block may appear twice).
  float k = float(ML_PARAMS.cut_block_size);
  SST_PRECISE float fx = (float(sp.x) + 0.5f) / k - 0.5f;
  SST_PRECISE float fy = (float(sp.y) + 0.5f) / k - 0.5f;
  int bx = int(floor(fx));
  int by = int(floor(fy));
  SST_PRECISE float tx = fx - float(bx);
  SST_PRECISE float ty = fy - float(by);
  uint blocks[4];
  float p[4];
  float sum = 0.0f;
  SST_PRECISE float d_max = ML_PARAMS.hybrid_d_max * sp.depth;
  for (int c = 0; c < 4; ++c) {
    int cx = clamp(bx + (c & 1), 0, int(ML_PARAMS.cut_blocks_x) - 1);
    int cy = clamp(by + (c >> 1), 0, int(ML_PARAMS.cut_blocks_y) - 1);
    blocks[c] = uint(cy) * ML_PARAMS.cut_blocks_x + uint(cx);
    CutGuide g = ML_CUT_GUIDE(blocks[c]);
    SST_PRECISE vec3 to_guide = sp.p - g.p;
    bool similar = g.valid != 0u && geometrically_similar(g.n, sp.basis.n, length3(to_guide), ML_PARAMS.hybrid_n_min,
                                                          d_max);
    SST_PRECISE float wx = (c & 1) != 0 ? tx : 1.0f - tx;
    SST_PRECISE float wy = (c >> 1) != 0 ? ty : 1.0f - ty;
    SST_PRECISE float bilinear = wx * wy;
    p[c] = similar ? bilinear : 0.0f;
    sum += p[c];
  }
  if (!(sum > 0.0f)) {  // no similar block: the mock cut
    for (uint j = 0u; j < ML_PARAMS.hybrid_mock_cut_size; ++j) hybrid_traverse(ML_CTX sp, ML_MOCK_CUT(j), ps, e);
    return e;
  }
  for (uint i = 0u; i < ML_PARAMS.hybrid_cut_size; ++i) {
    SST_PRECISE float u = pixel_sampler_get1d(ps) * sum;
    int c = 0;
    while (c < 3 && (u >= p[c] || p[c] == 0.0f)) {
      u -= p[c];
      ++c;
    }
    if (p[c] == 0.0f) {  // rounding past the last weight: the largest (first of equals)
      c = 0;
      for (int j = 1; j < 4; ++j)
        if (p[c] < p[j]) c = j;
    }
    uint block = blocks[c];
    if (i < ML_CUT_SIZE(block)) hybrid_traverse(ML_CTX sp, ML_CUT_NODE(block * ML_PARAMS.cut_max_size + i), ps, e);
  }
  return e;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_HYBRID_HYBRID_ESTIMATE_H
