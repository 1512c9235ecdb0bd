// `sst`, stochastic substitute trees (Tatzgern et al. 2020, section 4), the estimate at one
// shading point (shared C++/GLSL source; sst_sampler.h describes the method and its parameters).
// Per sample: pick a lobe, walk the tree with w = M * G * I, stop at a leaf or (diffuse lobe, with
// substitutes) at the first suitable node, whose Gaussian gives a point light; shade it divided by
// the walk's and the lobe's probability.
#ifndef SST_CORE_MANYLIGHT_SST_SST_ESTIMATE_H
#define SST_CORE_MANYLIGHT_SST_SST_ESTIMATE_H
#include "core/math/box_bounds.h"
#include "core/math/accurate_math.h"
#include "core/manylight/estimator.h"

SST_BEGIN

SST_CONSTANT float kSstTwoPi = 6.28318530717958647692f;

// What M and G need of the shading point and the lobe, the same at every node of a walk: taken
// once per walk instead of at each of its 30-odd weights.
struct SstWalkBound {
  bool glossy;
  float diffuse_scale;  // diffuse lobe: luminance(diffuse) / pi
  vec3 mirror;          // glossy lobe: wo mirrored about the shading normal, in world space
  vec3 inv_mirror;      // 1 / mirror per axis, where mirror's component is not 0
  float floor_value;    // glossy lobe: keeps every box above the surface reachable
  float eps2;           // G's floor on the squared distance
  float floor_fraction;  // and on d over the box's diagonal (LightTreeParams::node_distance_floor)
};

// sp.brdf: the lobe's part (sst_lobe_brdf).
SST_FUNC SstWalkBound sst_walk_bound(SST_IN(ShadingPoint) sp, bool glossy, float eps, float floor_fraction) {
  SstWalkBound b;
  b.floor_fraction = floor_fraction;
  b.glossy = glossy;
  SST_PRECISE float diffuse_scale = luminance(sp.brdf.diffuse) * kInvPi;
  b.diffuse_scale = diffuse_scale;
  vec3 wo_world = to_world(sp.basis, sp.wo);
  SST_PRECISE vec3 mirror = 2.0f * dot3(sp.basis.n, wo_world) * sp.basis.n - wo_world;
  b.mirror = mirror;
  for (int a = 0; a < 3; ++a) b.inv_mirror[a] = mirror[a] == 0.0f ? 0.0f : 1.0f / mirror[a];
  SST_PRECISE float floor_value = 1e-3f * max(luminance(sp.brdf.f0), 1e-6f);
  b.floor_value = floor_value;
  // eps = 0 would divide by 0 at a box containing x: floored far below any scene scale.
  SST_PRECISE float eps2 = max(eps * eps, 1e-30f);
  b.eps2 = eps2;
  return b;
}

// Whether the ray x + tR (t >= 0) meets the box (slab test); inv_r: 1 / R per axis.
SST_FUNC bool sst_ray_hits_box(vec3 x, vec3 r, vec3 inv_r, vec3 lo, vec3 hi) {
  float t0 = 0.0f;
  float t1 = kInf;
  for (int a = 0; a < 3; ++a) {
    if (r[a] == 0.0f) {
      if (x[a] < lo[a] || x[a] > hi[a]) return false;
      continue;
    }
    SST_PRECISE float ta = (lo[a] - x[a]) * inv_r[a];
    SST_PRECISE float tb = (hi[a] - x[a]) * inv_r[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
    if (t0 > t1) return false;
  }
  return true;
}

// The direction toward the box closest to the mirror direction R: R when it hits the box, else
// toward the box point nearest to the ray (a cheap stand-in for the exact minimiser).
SST_FUNC vec3 sst_glossy_direction(vec3 x, vec3 r, vec3 inv_r, vec3 lo, vec3 hi) {
  if (sst_ray_hits_box(x, r, inv_r, lo, hi)) return r;
  SST_PRECISE vec3 to_center = box_center(lo, hi) - x;
  float t = max(0.0f, dot3(to_center, r));
  SST_PRECISE vec3 q = x + t * r;
  SST_PRECISE vec3 d = clamp(q, lo, hi) - x;
  float len = length3(d);
  SST_PRECISE vec3 dn = d / len;
  return len > 0.0f ? dn : r;
}

// M: the lobe's BRDF bound times the cosine bound over the node's box (box_cos_bound_in_frame of
// its box, given; sp.brdf: the lobe's part).
SST_FUNC float sst_material_bound(SST_IN(LightNode) node, SST_IN(ShadingPoint) sp, SST_IN(SstWalkBound) b,
                                  float cos_bound) {
  if (!(cos_bound > 0.0f)) return 0.0f;
  if (!b.glossy) {
    SST_PRECISE float m = b.diffuse_scale * cos_bound;
    return m;
  }
  vec3 wi = to_local(sp.basis, sst_glossy_direction(sp.p, b.mirror, b.inv_mirror, node.bounds_lo, node.bounds_hi));
  float f = luminance(brdf_eval(sp.brdf, sp.wo, wi));
  SST_PRECISE float with_floor = f + b.floor_value;
  SST_PRECISE float m = (is_finite(f) ? with_floor : b.floor_value) * cos_bound;
  return m;
}

// w = M * G * I, G = 1 / max(d^2, eps^2), d floored at b.floor_fraction times the box's diagonal;
// cos_bound: box_cos_bound_in_frame of the node's box.
SST_FUNC float sst_node_weight(SST_IN(LightNode) node, SST_IN(ShadingPoint) sp, SST_IN(SstWalkBound) b,
                               float cos_bound) {
  if (light_node_empty(node)) return 0.0f;
  float intensity = luminance(node.intensity);
  if (!(intensity > 0.0f)) return 0.0f;
  float m = sst_material_bound(node, sp, b, cos_bound);
  if (!(m > 0.0f)) return 0.0f;
  float g = 1.0f / max(box_distance2_floored(node.bounds_lo, node.bounds_hi, sp.p, b.floor_fraction), b.eps2);
  SST_PRECISE float w = m * g * intensity;
  return w;
}

// (w_left, w_right): the two children's cosine bounds side by side (box_cos_bound_pair_in_frame).
SST_FUNC vec2 sst_child_weights(SST_IN(LightNode) left, SST_IN(LightNode) right, SST_IN(ShadingPoint) sp,
                                SST_IN(SstWalkBound) b) {
  vec2 cos_bound =
      box_cos_bound_pair_in_frame(left.bounds_lo, left.bounds_hi, right.bounds_lo, right.bounds_hi, sp.p, sp.basis);
  return vec2(sst_node_weight(left, sp, b, cos_bound.x), sst_node_weight(right, sp, b, cos_bound.y));
}

// The part of the BRDF the lobe shades.
SST_FUNC Brdf sst_lobe_brdf(Brdf b, bool glossy) {
  if (glossy) {
    b.diffuse = vec3(0.0f);
  } else {
    b.specular = false;
    b.f0 = vec3(0.0f);
  }
  return b;
}

// Three standard normal deviates from two 2D uniforms (Box-Muller).
SST_FUNC vec3 sst_standard_normals(vec2 a, vec2 b) {
  // 1 - u is in (0, 1]: the logarithm stays finite.
  float ra = sqrt(-2.0f * accurate_log(max(1.0f - a.x, 1e-30f)));
  float rb = sqrt(-2.0f * accurate_log(max(1.0f - b.x, 1e-30f)));
  SST_PRECISE float pa = kSstTwoPi * a.y;
  SST_PRECISE float pb = kSstTwoPi * b.y;
  SST_PRECISE vec3 r = vec3(ra * accurate_cos(pa), ra * accurate_sin(pa), rb * accurate_cos(pb));
  return r;
}

// A light position from the node's Gaussian (the normal deviates scaled by the standard
// deviations in the node's basis about the mean), clamped into its box: the box holds every VPL
// of the node, and a draw outside it would be light from nowhere.
SST_FUNC vec3 sst_substitute_position(SST_IN(LightNode) node, vec3 normals) {
  vec3 sd = vec3(sqrt(max(node.variance.x, 0.0f)), sqrt(max(node.variance.y, 0.0f)), max(node.sigma_z, 0.0f));
  SST_PRECISE vec3 scaled = sd * normals;
  vec3 offset = to_world(basis_from_normal(node.normal), scaled);
  SST_PRECISE vec3 p = node.mean + (is_finite3(offset) ? offset : vec3(0.0f));
  return clamp(p, node.bounds_lo, node.bounds_hi);
}

SST_FUNC IndirectEstimate estimate_sst(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  IndirectEstimate e = indirect_estimate_zero();
  float p_glossy = sp.brdf.specular ? clamp(brdf_specular_probability(sp.brdf, sp.wo), 0.0f, 1.0f) : 0.0f;
  bool glossy = false;
  float p_lobe = 1.0f;
  if (p_glossy >= 1.0f) {
    glossy = true;
  } else if (p_glossy > 0.0f) {
    glossy = pixel_sampler_get1d(ps) < p_glossy;
    p_lobe = glossy ? p_glossy : 1.0f - p_glossy;
  }
  ShadingPoint lp = sp;
  if (sp.brdf.specular) lp.brdf = sst_lobe_brdf(sp.brdf, glossy);
  bool stop_at_suitable = !glossy && ML_PARAMS.sst_substitutes != 0u;
  SstWalkBound bound = sst_walk_bound(lp, glossy, ML_PARAMS.sst_eps, ML_PARAMS.node_distance_floor);

  TreeWalk walk = tree_walk_begin(ML_PARAMS.tree_root);
  for (uint step = 0u; step < ML_PARAMS.tree_node_count && walk.node != kNoNode; ++step) {
    walk.nodes_visited += 1u;
    LightNode node = ML_NODE(walk.node);
    bool leaf = light_node_is_leaf(node);
    if (leaf || (stop_at_suitable && light_node_suitable(node) && ml_substitute_allowed(ML_CTX lp, node))) {
      Vpl vpl;
      if (leaf) {
        if (node.left == kNoNode || node.left >= ML_PARAMS.vpl_count) break;
        vpl = ML_VPL(node.left);
      } else {
        vec2 a = pixel_sampler_get2d(ps);
        vec2 b = pixel_sampler_get2d(ps);
        vpl.position = sst_substitute_position(node, sst_standard_normals(a, b));
        vpl.normal = node.normal;
        vpl.intensity = node.intensity;
      }
      vec3 c = shade_vpl(ML_CTX lp, vpl, e.shadow_rays);
      e.value = divide_by_probability(c, tree_probability_times(walk.probability, p_lobe));
      break;
    }
    vec2 w = sst_child_weights(ML_NODE(node.left), ML_NODE(node.right), lp, bound);
    tree_walk_step(walk, node, w, ps);
  }
  e.nodes_visited = walk.nodes_visited;
  return e;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_SST_SST_ESTIMATE_H
