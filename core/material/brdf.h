// The glTF metallic-roughness BRDF of METHODS.md §0, in a local shading frame (z = normal):
//   f = (1 - metallic) * baseColor / pi  +  D * G * F / (4 |n.wo| |n.wi|)
// D: GGX with alpha = roughness^2; G: Smith height-correlated masking-shadowing; F: Schlick with
// F0 = mix(0.04, baseColor, metallic). Diffuse-only mode keeps just Lambert baseColor / pi.
// The two lobes are added (not energy-mixed), as METHODS.md specifies for every method.
#pragma once
#include "core/math/math.h"

namespace sst {

struct BrdfSample {
  vec3 wi{0.0f};     // local frame
  vec3 weight{0.0f};  // f * cos / pdf
  float pdf = 0.0f;  // solid angle, of the mixture of both lobes
};

struct Brdf {
  vec3 diffuse{0.0f};  // (1 - metallic) * baseColor
  vec3 f0{0.0f};
  float alpha = 1.0f;  // clamped away from 0: a perfect mirror is a delta the samplers don't model
  bool specular = false;

  static Brdf from_material(vec3 base_color, float metallic, float roughness, bool diffuse_only);

  vec3 eval(vec3 wo, vec3 wi) const;  // f(wo, wi), without the cosine
  float pdf(vec3 wo, vec3 wi) const;
  // Returns false when no direction could be drawn (e.g. wo below the surface).
  // u.x chooses the lobe and is reused, remapped, for the direction.
  bool sample(vec3 wo, vec2 u, BrdfSample& out) const;
  // The probability of choosing the specular lobe when sampling.
  float specular_probability(vec3 wo) const;
};

// Shared pieces, also used by the many-light samplers' bounds.
float ggx_d(float n_dot_h, float alpha);
float smith_g2_height_correlated(float n_dot_wo, float n_dot_wi, float alpha);
vec3 schlick_fresnel(vec3 f0, float cos_theta);

}  // namespace sst
