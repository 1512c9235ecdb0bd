// The GLSL twin of core/manylight/sst_sampler.cpp: `sst`, stochastic substitute trees (Tatzgern
// et al. 2020, §4). Per sample: pick a lobe (glossy with brdf_specular_probability), walk the
// tree with w = M * G * I (M: the lobe's BRDF bound times the cosine bound over the box;
// G = 1 / max(d^2, eps^2); I = lum(intensity)), stop at a leaf or, for the diffuse lobe with
// substitutes, at the first suitable node, whose Gaussian gives a point light; shade it divided
// by the walk's and the lobe's probability. See sst_sampler.h for the method.
// The weights are float here, double on the CPU (see tree_walk.glsl).
#ifndef SST_GPU_SHADERS_INDIRECT_SST_GLSL
#define SST_GPU_SHADERS_INDIRECT_SST_GLSL
#include "core/lighttree/box_bounds.h"
#include "gpu/shaders/indirect/tree_walk.glsl"

const float kSstTwoPi = 6.28318530717958647692;

// Whether the ray x + tR (t >= 0) meets the box (slab test).
bool sst_ray_hits_box(vec3 x, vec3 r, vec3 lo, vec3 hi) {
  float t0 = 0.0, t1 = kInf;
  for (int a = 0; a < 3; ++a) {
    if (r[a] == 0.0) {
      if (x[a] < lo[a] || x[a] > hi[a]) return false;
      continue;
    }
    float inv = 1.0 / r[a];
    precise float ta = (lo[a] - x[a]) * inv, tb = (hi[a] - x[a]) * inv;
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
    if (t0 > t1) return false;
  }
  return true;
}

// The direction toward the box closest to the mirror direction R (R when it hits the box).
vec3 sst_glossy_direction(vec3 x, vec3 r, vec3 lo, vec3 hi) {
  if (sst_ray_hits_box(x, r, lo, hi)) return r;
  precise vec3 to_center = box_center(lo, hi) - x;
  float t = max(0.0, dot3(to_center, r));
  precise vec3 q = x + t * r;
  precise vec3 d = clamp(q, lo, hi) - x;
  float len = length3(d);
  precise vec3 dn = d / len;
  return len > 0.0 ? dn : r;
}

// The lobe's BRDF bound times the cosine bound over the node's box (sp.brdf: the lobe's part).
float sst_material_bound(LightNode node, ShadingPoint sp, bool glossy) {
  float cos_bound = box_cos_bound(node.bounds_lo, node.bounds_hi, sp.p, sp.basis.n);
  if (!(cos_bound > 0.0)) return 0.0;
  if (!glossy) {
    precise float m = luminance(sp.brdf.diffuse) * kInvPi * cos_bound;
    return m;
  }
  vec3 wo_world = to_world(sp.basis, sp.wo);
  precise vec3 mirror = 2.0 * dot3(sp.basis.n, wo_world) * sp.basis.n - wo_world;
  vec3 wi = to_local(sp.basis, sst_glossy_direction(sp.p, mirror, node.bounds_lo, node.bounds_hi));
  float f = luminance(brdf_eval(sp.brdf, sp.wo, wi));
  // The floor keeps every box above the surface reachable.
  precise float floor_value = 1e-3 * max(luminance(sp.brdf.f0), 1e-6);
  precise float with_floor = f + floor_value;
  precise float m = (is_finite(f) ? with_floor : floor_value) * cos_bound;
  return m;
}

float sst_node_weight(LightNode node, ShadingPoint sp, float eps, bool glossy) {
  if (node.vpl_count == 0u) return 0.0;
  float intensity = luminance(node.intensity);
  if (!(intensity > 0.0)) return 0.0;
  float m = sst_material_bound(node, sp, glossy);
  if (!(m > 0.0)) return 0.0;
  // eps = 0 would divide by 0 at a box containing x: floored far below any scene scale.
  precise float eps2 = max(eps * eps, 1e-30);
  float g = 1.0 / max(box_distance2_min(node.bounds_lo, node.bounds_hi, sp.p), eps2);
  precise float w = m * g * intensity;
  return w;
}

// lobe_brdf: the part of the BRDF the lobe shades.
Brdf sst_lobe_brdf(Brdf b, bool glossy) {
  if (glossy) {
    b.diffuse = vec3(0.0);
  } else {
    b.specular = false;
    b.f0 = vec3(0.0);
  }
  return b;
}

// Three standard normal deviates from two 2D uniforms (Box-Muller).
vec3 sst_standard_normals(vec2 a, vec2 b) {
  // 1 - u is in (0, 1]: the logarithm stays finite.
  float ra = sqrt(-2.0 * log(max(1.0 - a.x, 1e-30)));
  float rb = sqrt(-2.0 * log(max(1.0 - b.x, 1e-30)));
  precise float pa = kSstTwoPi * a.y, pb = kSstTwoPi * b.y;
  precise vec3 r = vec3(ra * cos(pa), ra * sin(pa), rb * cos(pb));
  return r;
}

// A light position from the node's Gaussian, clamped into its box.
vec3 sst_substitute_position(LightNode node, vec3 normals) {
  vec3 sd = vec3(sqrt(max(node.variance.x, 0.0)), sqrt(max(node.variance.y, 0.0)), max(node.sigma_z, 0.0));
  precise vec3 scaled = sd * normals;
  vec3 offset = to_world(basis_from_normal(node.normal), scaled);
  precise vec3 p = node.mean + (is_finite3(offset) ? offset : vec3(0.0));
  return clamp(p, node.bounds_lo, node.bounds_hi);
}

IndirectEstimate estimate_sst(ShadingPoint sp, inout PixelSampler ps) {
  IndirectEstimate e = indirect_estimate_zero();
  float p_glossy = sp.brdf.specular ? clamp(brdf_specular_probability(sp.brdf, sp.wo), 0.0, 1.0) : 0.0;
  bool glossy = false;
  float p_lobe = 1.0;
  if (p_glossy >= 1.0) {
    glossy = true;
  } else if (p_glossy > 0.0) {
    glossy = pixel_sampler_get1d(ps) < p_glossy;
    p_lobe = glossy ? p_glossy : 1.0 - p_glossy;
  }
  ShadingPoint lp = sp;
  if (sp.brdf.specular) lp.brdf = sst_lobe_brdf(sp.brdf, glossy);

  bool stop_at_suitable = !glossy && ml_params.sst_substitutes != 0u;
  TreeTraversal t = traverse_tree(lp, TreeWalk(TREE_WEIGHTS_SST, ml_params.sst_eps, glossy, stop_at_suitable), ps);
  e.nodes_visited = t.nodes_visited;
  if (t.node == ML_NO_NODE) return e;
  LightNode node = ml_nodes[t.node];
  Vpl vpl;
  if ((node.flags & ML_NODE_LEAF) != 0u) {
    if (node.left == ML_NO_NODE || node.left >= ml_params.vpl_count) return e;
    vpl = ml_vpl(node.left);
  } else {
    vec2 a = pixel_sampler_get2d(ps);
    vec2 b = pixel_sampler_get2d(ps);
    vpl = Vpl(sst_substitute_position(node, sst_standard_normals(a, b)), node.normal, node.intensity);
  }
  vec3 c = shade_vpl(lp, vpl, e.shadow_rays);
  e.value = divide_by_probability(c, tree_probability_times(t.probability, p_lobe));
  return e;
}

#endif
