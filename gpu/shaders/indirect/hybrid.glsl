// The GLSL twin of core/manylight/hybrid_sampler.cpp: `hybrid`, shallow light cuts over a
// stochastic substitute tree (the hybrid thesis, ch. 5). The pixel blends the cuts of its four
// nearest blocks (built on the CPU at the block centres, uploaded) index by index: for cut index
// i one of the four similar blocks is drawn by bilinear weight, and the pixel walks from that
// cut's node i with expected-contribution weights to a leaf or a suitable node (a point light
// drawn from its Gaussian); with no similar block it walks from every node of the mock cut.
// Float throughout, as on the CPU.
#ifndef SST_GPU_SHADERS_INDIRECT_HYBRID_GLSL
#define SST_GPU_SHADERS_INDIRECT_HYBRID_GLSL
#include "core/lighttree/box_bounds.h"

// hybrid_weight: lum(I) G_avg / max(d^2, c^2), G_avg the mean over the box corners of
// max(n . normalize(corner - x), 0).
float hybrid_weight(LightNode node, vec3 x, vec3 n, float clamp_distance) {
  if (node.vpl_count == 0u) return 0.0;
  float g = 0.0;
  for (int c = 0; c < 8; ++c) {
    vec3 corner = vec3((c & 1) != 0 ? node.bounds_hi.x : node.bounds_lo.x,
                       (c & 2) != 0 ? node.bounds_hi.y : node.bounds_lo.y,
                       (c & 4) != 0 ? node.bounds_hi.z : node.bounds_lo.z);
    precise vec3 d = corner - x;
    float len = length3(d);
    precise float cosine = dot3(n, d) / len;
    if (len > 0.0) g += max(cosine, 0.0);
  }
  precise float c2 = clamp_distance * clamp_distance;
  float d2 = max(box_distance2_min(node.bounds_lo, node.bounds_hi, x), c2);
  precise float w = luminance(node.intensity) * (g * 0.125) / d2;
  return is_finite(w) ? w : 0.0;
}

// Two standard normal deviates (Box-Muller).
vec2 hybrid_normal_pair(inout PixelSampler ps) {
  vec2 u = pixel_sampler_get2d(ps);
  float r = sqrt(-2.0 * log(1.0 - u.x));  // u.x < 1: finite
  precise float phi = 2.0 * kPi * u.y;
  precise vec2 v = vec2(r * cos(phi), r * sin(phi));
  return v;
}

// A point light from a suitable node's substitute distribution, clamped into its box.
Vpl hybrid_sample_substitute(LightNode node, inout PixelSampler ps) {
  vec2 a = hybrid_normal_pair(ps);
  vec2 b = hybrid_normal_pair(ps);
  vec3 sd = sqrt(max(node.variance, vec3(0.0)));
  precise vec3 scaled = vec3(a.x, a.y, b.x) * sd;
  vec3 offset = to_world(basis_from_normal(node.normal), scaled);
  precise vec3 p = node.mean + offset;
  return Vpl(clamp(p, node.bounds_lo, node.bounds_hi), node.normal, node.intensity);
}

// One walk from cut node `from`; adds to e.
void hybrid_traverse(ShadingPoint sp, uint from, inout PixelSampler ps, inout IndirectEstimate e) {
  uint i = from;
  float prob = 1.0;
  for (uint step = 0u; step < ml_params.tree_node_count; ++step) {  // bound: a malformed tree
    ++e.nodes_visited;
    LightNode node = ml_nodes[i];
    if (node.vpl_count == 0u) return;
    if ((node.flags & ML_NODE_LEAF) != 0u) {
      vec3 c = shade_vpl(sp, ml_vpl(node.left), e.shadow_rays);
      e.value += c / prob;
      return;
    }
    if ((node.flags & ML_NODE_SUITABLE) != 0u) {  // close enough to a flat patch: its substitute
      Vpl v = hybrid_sample_substitute(node, ps);
      vec3 c = shade_vpl(sp, v, e.shadow_rays);
      e.value += c / prob;
      return;
    }
    float w0 = hybrid_weight(ml_nodes[node.left], sp.p, sp.basis.n, ml_params.clamp_distance);
    float w1 = hybrid_weight(ml_nodes[node.right], sp.p, sp.basis.n, ml_params.clamp_distance);
    precise float w = w0 + w1;
    if (!(w > 0.0)) return;  // neither child is expected to contribute: no backtracking
    float p0 = w0 / w;
    bool left = pixel_sampler_get1d(ps) < p0;
    prob *= left ? p0 : 1.0 - p0;
    i = left ? node.left : node.right;
  }
}

IndirectEstimate estimate_hybrid(ShadingPoint sp, inout PixelSampler ps) {
  IndirectEstimate e = indirect_estimate_zero();
  if (ml_params.tree_root == ML_NO_NODE) return e;
  // The four block centres around the pixel and their bilinear weights (clamped at the border).
  float k = float(ml_params.cut_block_size);
  precise float fx = (float(sp.x) + 0.5) / k - 0.5, fy = (float(sp.y) + 0.5) / k - 0.5;
  int bx = int(floor(fx)), by = int(floor(fy));
  precise float tx = fx - float(bx), ty = fy - float(by);
  uint blocks[4];
  float p[4];
  float sum = 0.0;
  for (int c = 0; c < 4; ++c) {
    int cx = clamp(bx + (c & 1), 0, int(ml_params.cut_blocks_x) - 1);
    int cy = clamp(by + (c >> 1), 0, int(ml_params.cut_blocks_y) - 1);
    blocks[c] = uint(cy) * ml_params.cut_blocks_x + uint(cx);
    CutGuide g = ml_cut_guides[blocks[c]];
    precise vec3 to_guide = sp.p - g.p;
    bool similar = g.valid != 0u && dot3(g.n, sp.basis.n) > ml_params.hybrid_n_min &&
                   length3(to_guide) < ml_params.hybrid_d_max_abs;
    precise float wx = (c & 1) != 0 ? tx : 1.0 - tx, wy = (c >> 1) != 0 ? ty : 1.0 - ty;
    precise float bilinear = wx * wy;
    p[c] = similar ? bilinear : 0.0;
    sum += p[c];
  }
  if (!(sum > 0.0)) {  // no similar block: the mock cut
    for (uint j = 0u; j < ml_params.hybrid_mock_cut_size; ++j) hybrid_traverse(sp, ml_mock_cut[j], ps, e);
    return e;
  }
  for (uint i = 0u; i < ml_params.hybrid_cut_size; ++i) {
    precise float u = pixel_sampler_get1d(ps) * sum;
    int c = 0;
    while (c < 3 && (u >= p[c] || p[c] == 0.0)) {
      u -= p[c];
      ++c;
    }
    if (p[c] == 0.0) {  // rounding past the last weight: the largest (first of equals)
      c = 0;
      for (int j = 1; j < 4; ++j)
        if (p[c] < p[j]) c = j;
    }
    uint block = blocks[c];
    if (i < ml_cut_sizes[block]) hybrid_traverse(sp, ml_cut_nodes[block * ml_params.cut_max_size + i], ps, e);
  }
  return e;
}

#endif
