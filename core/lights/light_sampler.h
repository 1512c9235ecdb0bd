// Direct-light sampling over every light of a scene: punctual lights (point, spot, directional)
// and emissive triangles, one light picked in proportion to its power (METHODS.md §0), then a
// point on it: uniform by solid angle for a triangle that subtends a large angle from the
// shading point, uniform by area otherwise. Also answers the pdf of hitting an emissive
// triangle by BSDF sampling, for multiple importance sampling. Also samples where light leaves
// the lights (`sample_emission`), for light paths: instant radiosity's VPLs (METHODS.md §1).
#pragma once
#include <vector>

#include "core/math/math.h"
#include "core/sampling/discrete_distribution.h"
#include "core/scene/scene.h"

namespace sst {

struct LightSample {
  vec3 wi{0.0f};         // unit, from the shading point toward the light
  float distance = 0.0f;  // to the light point; kInf for directional lights
  vec3 li{0.0f};         // radiance (area) / intensity / d^2 (point, spot) / irradiance (directional)
  float pdf = 0.0f;      // solid-angle pdf incl. the light's pick probability; for delta lights the pick probability
  bool delta = false;    // point, spot, directional: cannot be hit by BSDF sampling
  vec3 point{0.0f};      // the sampled point (point/spot position; unused for directional)
  vec3 normal{0.0f};     // geometric normal at the point (0 for punctual lights)
};

// The start of a light path: where it leaves a light, which way, and the flux it carries.
// `weight` is Le cos / (pdf_pick * pdf_position * pdf_direction) (Le cos -> intensity for point
// and spot lights, irradiance for directional ones), so its mean over samples is the total
// power of all lights, in W per RGB channel: N paths each carrying weight / N deliver every
// light's flux in expectation.
struct EmissionSample {
  vec3 position{0.0f};   // on the light (for a directional light: on a disc outside the scene)
  vec3 normal{0.0f};     // unit normal of the emitting side of a triangle; 0 for punctual lights
  vec3 direction{0.0f};  // unit, the direction the light travels
  vec3 weight{0.0f};     // flux carried, W per RGB channel (see above)
  uint32_t light = 0;    // index in the light distribution (punctual lights first, then triangles)
};

// Whether an emissive triangle is sampled by solid angle (rather than by area) from p: a pure
// function of the geometry, so sampling and the MIS pdf of a BSDF hit always agree.
bool uses_solid_angle_sampling(vec3 p, vec3 v0, vec3 v1, vec3 v2);
// Estimated solid angle (sr) above which a triangle is sampled by solid angle. Measured on the
// Cornell box and the staircase: the RMSE of area sampling matches below it, and the extra
// trigonometry of every solid-angle sample is paid only where it helps.
inline constexpr float kSolidAngleSamplingThreshold = 0.05f;

// glTF spot attenuation: smooth step between the outer and inner cone cosines, squared.
float spot_attenuation(const PunctualLight& light, vec3 light_to_point_unit);

class LightSampler {
 public:
  LightSampler() = default;
  explicit LightSampler(const Scene& scene);

  bool empty() const { return distribution_.empty(); }
  size_t light_count() const { return distribution_.size(); }
  size_t emissive_triangle_count() const { return emissive_triangles_.size(); }

  // Samples a light for shading point p with one 2D sample (u.x picks the light and is reused,
  // remapped, for the point on it). Returns false when no light can contribute.
  bool sample(vec3 p, vec2 u, LightSample& out) const;
  // Solid-angle pdf that `sample` would pick the point y on emissive triangle `tri` from p
  // (0 for a triangle that is not a light).
  float pdf_emissive_hit(vec3 p, uint32_t tri, vec3 y, vec3 ng_light) const;

  // Samples the start of a light path: a light picked with u_pick in proportion to its power
  // (the same distribution as `sample`), a position on it (u_pos) and a direction (u_dir):
  //   point        uniform sphere, pdf 1/(4 pi)                weight 4 pi I / pick
  //   spot         uniform in the outer cone, pdf 1/(2 pi (1 - cos_outer))
  //                                                             weight 2 pi (1 - cos_outer) I att(w) / pick
  //   directional  uniform on the disc of the scene's bounding sphere (radius r) perpendicular to
  //                the direction, just over r upstream of its centre, pdf 1/(pi r^2)
  //                                                             weight pi r^2 E / pick
  //   triangle     uniform on the triangle (pdf 1/A), cosine about the emitting side (pdf cos/pi,
  //                halved when a double-sided emitter picks a side with probability 1/2)
  //                                                             weight Le pi A (x2 double-sided) / pick
  // The pick has its own number (unlike `sample`, which remaps one): with a million emissive
  // triangles a remapped 24-bit number would leave a few bits for the position on each.
  // Returns false (the path carries nothing) when the weight would be zero or not finite.
  bool sample_emission(float u_pick, vec2 u_pos, vec2 u_dir, EmissionSample& out) const;

  // The tables, read-only, for packing them for the GPU (gpu/light_upload.h).
  const DiscreteDistribution& distribution() const { return distribution_; }
  const std::vector<uint32_t>& emissive_triangles() const { return emissive_triangles_; }
  const std::vector<float>& emissive_triangle_areas() const { return triangle_area_; }
  const std::vector<uint32_t>& light_of_triangle() const { return light_of_triangle_; }

 private:
  bool emit_triangle(size_t k, vec2 u_pos, vec2 u_dir, EmissionSample& out) const;

  const Scene* scene_ = nullptr;
  DiscreteDistribution distribution_;     // over punctual lights first, then emissive triangles
  std::vector<uint32_t> emissive_triangles_;
  std::vector<float> triangle_area_;       // of each emissive triangle, same order
  std::vector<uint32_t> light_of_triangle_;  // triangle -> index in the distribution, or UINT32_MAX
};

}  // namespace sst
