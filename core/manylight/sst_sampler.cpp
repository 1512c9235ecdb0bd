#include "core/manylight/sst_sampler.h"

#include <cmath>

#include "core/lighttree/box_bounds.h"
#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/gpu_sampler_inputs.h"

namespace sst {
namespace {

constexpr float kTwoPi = 6.28318530717958647692f;
constexpr float kInvPiF = 0.31830988618379067154f;

// Whether the ray x + tR (t >= 0) meets the box (slab test).
bool ray_hits_box(vec3 x, vec3 r, const Bounds3& b) {
  float t0 = 0.0f, t1 = kInf;
  for (int a = 0; a < 3; ++a) {
    if (r[a] == 0.0f) {
      if (x[a] < b.lo[a] || x[a] > b.hi[a]) return false;
      continue;
    }
    float inv = 1.0f / r[a];
    float ta = (b.lo[a] - x[a]) * inv, tb = (b.hi[a] - x[a]) * inv;
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
    if (t0 > t1) return false;
  }
  return true;
}

// The direction toward the box that is closest to the mirror direction R: R when it hits the
// box, else toward the box point nearest to the ray (a cheap stand-in for the exact minimiser).
vec3 glossy_direction(vec3 x, vec3 r, const Bounds3& b) {
  if (ray_hits_box(x, r, b)) return r;
  float t = std::max(0.0f, glm::dot(b.center() - x, r));
  vec3 d = glm::clamp(x + t * r, b.lo, b.hi) - x;
  float len = glm::length(d);
  return len > 0.0f ? d / len : r;
}

double material_bound(const LightNode& node, const ShadingPoint& point, SstLobe lobe) {
  float cos_bound = box_cos_bound(node.bounds(), point.p, point.basis.n);
  if (!(cos_bound > 0.0f)) return 0.0;
  if (lobe == SstLobe::diffuse) return double(luminance(point.brdf.diffuse)) * kInvPiF * cos_bound;
  vec3 wo_world = to_world(point.basis, point.wo);
  vec3 mirror = 2.0f * glm::dot(point.basis.n, wo_world) * point.basis.n - wo_world;
  vec3 wi = to_local(point.basis, glossy_direction(point.p, mirror, node.bounds()));
  float f = luminance(brdf_eval(point.brdf, point.wo, wi));
  // The floor keeps every box above the surface reachable (see the header).
  float floor = 1e-3f * std::max(luminance(point.brdf.f0), 1e-6f);
  return double(std::isfinite(f) ? f + floor : floor) * cos_bound;
}

}  // namespace

double sst_node_weight(const LightNode& node, const ShadingPoint& point, float eps, SstLobe lobe) {
  if (node.empty()) return 0.0;
  double intensity = luminance(node.intensity);
  if (!(intensity > 0.0)) return 0.0;
  double m = material_bound(node, point, lobe);
  if (!(m > 0.0)) return 0.0;
  // eps = 0 would divide by 0 at a box containing x: floor it far below any scene scale.
  double eps2 = std::max(double(eps) * double(eps), 1e-30);
  double g = 1.0 / std::max(double(box_distance2_min(node.bounds(), point.p)), eps2);
  return m * g * intensity;
}

ChildWeights sst_weights(const ShadingPoint& point, float eps, SstLobe lobe) {
  return [&point, eps, lobe](const LightNode& l, const LightNode& r) -> std::array<double, 2> {
    return {sst_node_weight(l, point, eps, lobe), sst_node_weight(r, point, eps, lobe)};
  };
}

StopRule sst_stop_rule(SstLobe lobe, bool substitutes) {
  if (lobe == SstLobe::glossy || !substitutes) return stop_at_leaves;
  return [](const LightNode& n) { return n.is_leaf() || n.suitable(); };
}

Brdf lobe_brdf(const Brdf& brdf, SstLobe lobe) {
  Brdf b = brdf;
  if (lobe == SstLobe::diffuse) {
    b.specular = false;
    b.f0 = vec3(0.0f);
  } else {
    b.diffuse = vec3(0.0f);
  }
  return b;
}

vec3 standard_normals(vec2 a, vec2 b) {
  // 1 - u is in (0, 1]: the logarithm stays finite.
  float ra = std::sqrt(-2.0f * std::log(std::max(1.0f - a.x, 1e-30f)));
  float rb = std::sqrt(-2.0f * std::log(std::max(1.0f - b.x, 1e-30f)));
  return {ra * std::cos(kTwoPi * a.y), ra * std::sin(kTwoPi * a.y), rb * std::cos(kTwoPi * b.y)};
}

vec3 substitute_position(const LightNode& node, vec3 normals) {
  vec3 sd(std::sqrt(std::max(node.variance.x, 0.0f)), std::sqrt(std::max(node.variance.y, 0.0f)),
          std::max(node.sigma_z, 0.0f));
  vec3 offset = to_world(basis_from_normal(node.normal), sd * normals);
  vec3 p = node.mean + (is_finite(offset) ? offset : vec3(0.0f));
  // The box holds every VPL of the node: a draw outside it would be light from nowhere.
  return glm::clamp(p, node.bounds_lo, node.bounds_hi);
}

IndirectEstimate SstSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                      PixelSampler& sampler) const {
  IndirectEstimate e;
  float p_glossy = point.brdf.specular ? std::clamp(brdf_specular_probability(point.brdf, point.wo), 0.0f, 1.0f) : 0.0f;
  SstLobe lobe = SstLobe::diffuse;
  double p_lobe = 1.0;
  if (p_glossy >= 1.0f) {
    lobe = SstLobe::glossy;
  } else if (p_glossy > 0.0f) {
    bool glossy = pixel_sampler_get1d(sampler) < p_glossy;
    lobe = glossy ? SstLobe::glossy : SstLobe::diffuse;
    p_lobe = glossy ? p_glossy : 1.0 - p_glossy;
  }
  ShadingPoint lp = point;
  if (point.brdf.specular) lp.brdf = lobe_brdf(point.brdf, lobe);

  TreeTraversal t = traverse_tree(tree_, sst_weights(lp, sst_.distance_floor * tree_.length_scale, lobe), sst_stop_rule(lobe, sst_.substitutes),
                                  [&] { return pixel_sampler_get1d(sampler); });
  e.nodes_visited = t.nodes_visited;
  if (t.node == kNoNode) return e;
  const LightNode& node = tree_[t.node];
  Vpl vpl;
  if (node.is_leaf()) {
    if (node.vpl() == kNoNode || node.vpl() >= frame.vpls.size()) return e;
    vpl = frame.vpls[node.vpl()];
  } else {
    vec2 a = pixel_sampler_get2d(sampler), b = pixel_sampler_get2d(sampler);
    vpl = Vpl{substitute_position(node, standard_normals(a, b)), node.normal, node.intensity};
  }
  e.value = divide_by_probability(shade_vpl(frame, lp, vpl, &e.shadow_rays), t.probability * p_lobe);
  return e;
}

void SstSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_SST, out);
  set_tree_inputs(tree_, out);
  out.params.sst_eps = sst_.distance_floor * tree_.length_scale;  // the product estimate() forms
  out.params.sst_substitutes = sst_.substitutes ? 1u : 0u;
}

}  // namespace sst
