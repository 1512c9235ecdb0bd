// Direct-light sampling over every light of a scene: punctual lights (point, spot, directional)
// and emissive triangles, one light picked by the chosen LightSamplerKind (uniformly, in
// proportion to its power, or for the shading point down the emitter tree,
// core/lights/emitter_tree.h and docs/light-trees.md), then a point on it: uniform by solid
// angle for a triangle that subtends a large angle from the shading point, uniform by area
// otherwise. Also answers the pdf of hitting an emissive triangle by BSDF sampling, for multiple
// importance sampling. Also samples where light leaves the lights (`sample_emission`), for light
// paths: instant radiosity's VPLs (core/vpl/vpl_generator.h).
// LightSampler builds the tables (core/lights/light_layout.h); the sampling is
// core/lights/light_sample.h, shared with the GPU.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <string>

#include "core/lights/emitter_tree_build.h"
#include "core/lights/light_layout.h"
#include "core/math/math.h"
#include "core/sampling/discrete_distribution.h"
#include "core/scene/scene.h"
#include "core/shading/surface.h"

namespace sst {

// The tables light sampling reads, in the layout of core/lights/light_layout.h (the GPU uploads
// them as they are).
struct PackedLights {
  glsl::LightHeader header{};
  std::vector<glsl::LightPunctual> punctual;       // Scene::lights
  std::vector<glsl::LightCdfEntry> distribution;   // over all lights (empty when no light emits)
  std::vector<glsl::LightEmissive> emissive;       // the emissive triangles
  std::vector<uint32_t> light_of_triangle;         // per scene triangle; LIGHT_NONE if no light
  EmitterNodes tree;                               // the emitter tree (tree and slc samplers)

  size_t bytes() const;
};

// How a light is picked for a shading point (RenderOptions::light_sampler; LIGHT_SAMPLER_*).
enum class LightSamplerKind : uint32_t {
  Uniform = LIGHT_SAMPLER_UNIFORM,
  Power = LIGHT_SAMPLER_POWER,
  Tree = LIGHT_SAMPLER_TREE,
  Slc = LIGHT_SAMPLER_SLC,
};
// "uniform, power, tree, slc", for help and errors.
const char* light_sampler_names();
const char* light_sampler_name(LightSamplerKind kind);
// Throws sst::Error naming the valid values for an unknown name.
LightSamplerKind parse_light_sampler(const std::string& name);

}  // namespace sst

#define LIGHT_CTX_PARAM const ::sst::PackedLights &lights,
#define LIGHT_CTX lights,
#define LIGHT_HEADER lights.header
#define LIGHT_PUNCTUAL(i) lights.punctual[i]
#define LIGHT_CDF(i) lights.distribution[i]
#define LIGHT_EMISSIVE(k) lights.emissive[k]
#define LIGHT_OF_TRIANGLE(t) lights.light_of_triangle[t]
#define LIGHT_TREE(i) lights.tree[i]
#include "core/lights/light_sample.h"

namespace sst {

class LightSampler {
 public:
  LightSampler() = default;
  // `build`: how the tree and slc samplers' emitter tree is built; `distance`: the tree
  // sampler's distance rule (core/lights/emitter_tree_build.h).
  explicit LightSampler(const Scene& scene, LightSamplerKind kind = LightSamplerKind::Power,
                        EmitterTreeBuild build = EmitterTreeBuild::Saoh,
                        EmitterDistance distance = EmitterDistance::Centre);

  bool empty() const { return distribution_.empty(); }
  size_t light_count() const { return distribution_.size(); }
  size_t emissive_triangle_count() const { return packed_.emissive.size(); }

  LightSamplerKind kind() const { return kind_; }

  // Samples a light for shading point p with shading normal n (0: none) with one 2D sample (u.x
  // picks the light and is reused, remapped, for the point on it). Returns false when no light
  // can contribute. LightSample::pdf includes the pick's probability.
  bool sample(vec3 p, vec3 n, vec2 u, LightSample& out) const {
    return scene_ && light_sample(*scene_, packed_, p, n, u, out);
  }
  // Solid-angle pdf that `sample(p, n, ...)` would pick the point y on emissive triangle `tri`
  // (0 for a triangle that is not a light).
  float pdf_emissive_hit(vec3 p, vec3 n, uint32_t tri, vec3 y, vec3 ng_light) const {
    return scene_ ? light_pdf_emissive_hit(*scene_, packed_, p, n, tri, y, ng_light) : 0.0f;
  }
  // The probability that `sample(p, n, ...)` picks distribution entry `light` (pbrt-v4's
  // LightSampler::PMF(ctx, light)); the pick itself, for tests.
  float pmf(vec3 p, vec3 n, uint32_t light) const { return light_pick_pmf(packed_, p, n, light); }
  uint32_t pick(vec3 p, vec3 n, float u, float& pmf, float& u_remapped) const {
    return light_pick_for(packed_, p, n, u, pmf, u_remapped);
  }

  // Samples the start of a light path: a light picked with u_pick in proportion to its power
  // (the same distribution as `sample`), a position on it (u_pos) and a direction (u_dir):
  //   point        uniform sphere, pdf 1/(4 pi)                weight 4 pi I / pick
  //   spot         uniform in the outer cone, pdf 1/(2 pi (1 - cos_outer))
  //                                                             weight 2 pi (1 - cos_outer) I att(w) / pick
  //   directional  uniform on the disc of the scene's bounding sphere (radius r) perpendicular to
  //                the direction, just over r upstream of its centre, pdf 1/(pi r^2)
  //                                                             weight pi r^2 E / pick
  //                (with a focus, a mixture with the focus disc: weight E / (pdf pick))
  //   triangle     uniform on the triangle (pdf 1/A), cosine about the emitting side (pdf cos/pi,
  //                halved when a double-sided emitter picks a side with probability 1/2)
  //                                                             weight Le pi A (x2 double-sided) / pick
  // The pick has its own number (unlike `sample`, which remaps one): with a million emissive
  // triangles a remapped 24-bit number would leave a few bits for the position on each.
  // Returns false (the path carries nothing) when the weight would be zero or not finite.
  // `focus`: where directional lights aim most of their paths (EmissionFocus).
  bool sample_emission(float u_pick, vec2 u_pos, vec2 u_dir, EmissionSample& out,
                       const EmissionFocus& focus = emission_focus_none()) const {
    out = EmissionSample{};
    return scene_ && light_sample_emission(*scene_, packed_, u_pick, u_pos, u_dir, focus, out);
  }

  // The tables the sampling reads (and the GPU uploads).
  const PackedLights& packed() const { return packed_; }
  // The distribution in double precision, as it was summed: the reference whose picks the
  // tables' hi/lo CDF reproduces (tests compare the two).
  const DiscreteDistribution& distribution() const { return distribution_; }

 private:
  const Scene* scene_ = nullptr;
  LightSamplerKind kind_ = LightSamplerKind::Power;
  DiscreteDistribution distribution_;  // over punctual lights first, then emissive triangles
  PackedLights packed_;
};

}  // namespace sst
