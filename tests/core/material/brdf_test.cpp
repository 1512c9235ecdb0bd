#include "core/material/brdf.h"

#include <gtest/gtest.h>

#include "core/rng/hash_rng.h"
#include "core/sampling/sampling.h"

namespace sst {
namespace {

// Monte Carlo over the cosine-weighted hemisphere: albedo = integral f cos dw, and
// integral pdf dw (which must be 1 for a sampler that never fails below the horizon... or less).
struct Integrals {
  vec3 albedo{0.0f};
  double pdf_mass = 0.0;
};
Integrals integrate(const Brdf& b, vec3 wo, int n) {
  Integrals r;
  HashRng rng = hash_rng(11, 0, 0);
  for (int i = 0; i < n; ++i) {
    vec3 wi = sample_cosine_hemisphere(hash_rng_next(rng), hash_rng_next(rng));
    float pdf = cosine_hemisphere_pdf(wi.z);
    if (pdf <= 0.0f) continue;
    r.albedo += brdf_eval(b, wo, wi) * wi.z / pdf;
    r.pdf_mass += brdf_pdf(b, wo, wi) / pdf;
  }
  r.albedo /= float(n);
  r.pdf_mass /= n;
  return r;
}

TEST(Brdf, LambertReflectsItsAlbedo) {
  Brdf b = brdf_from_material(vec3(0.2f, 0.5f, 0.8f), 0.0f, 1.0f, true);
  Integrals r = integrate(b, glm::normalize(vec3(0.3f, 0.1f, 1.0f)), 20000);
  EXPECT_NEAR(r.albedo.x, 0.2f, 0.002f);
  EXPECT_NEAR(r.albedo.z, 0.8f, 0.008f);
  EXPECT_NEAR(r.pdf_mass, 1.0, 1e-6);
}

TEST(Brdf, DiffuseOnlyIgnoresMetallicAndRoughness) {
  Brdf b = brdf_from_material(vec3(0.5f), 1.0f, 0.0f, true);
  EXPECT_FALSE(b.specular);
  EXPECT_EQ(b.diffuse, vec3(0.5f));
}

TEST(Brdf, SampleWeightEqualsEvalCosOverPdf) {
  for (float roughness : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float metallic : {0.0f, 1.0f}) {
      Brdf b = brdf_from_material(vec3(0.9f, 0.6f, 0.3f), metallic, roughness, false);
      vec3 wo = glm::normalize(vec3(0.5f, -0.2f, 0.8f));
      HashRng rng = hash_rng(1, 2, 3);
      for (int i = 0; i < 2000; ++i) {
        BrdfSample s;
        if (!brdf_sample(b, wo, vec2(hash_rng_next(rng), hash_rng_next(rng)), s)) continue;
        ASSERT_GT(s.wi.z, 0.0f);
        vec3 expected = brdf_eval(b, wo, s.wi) * s.wi.z / brdf_pdf(b, wo, s.wi);
        ASSERT_NEAR(s.weight.x, expected.x, 1e-4f * std::max(1.0f, expected.x));
        ASSERT_TRUE(is_finite(s.weight));
      }
    }
}

TEST(Brdf, SampledDirectionsFollowThePdf) {
  // E over sampled wi of g(wi)/pdf(wi) = integral of g over the hemisphere where pdf > 0; with
  // g = cos/pi that integral is 1 when the pdf covers the hemisphere.
  Brdf b = brdf_from_material(vec3(0.5f), 0.0f, 0.4f, false);
  vec3 wo = glm::normalize(vec3(0.2f, 0.0f, 1.0f));
  HashRng rng = hash_rng(4, 5, 6);
  double sum = 0.0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    BrdfSample s;
    if (!brdf_sample(b, wo, vec2(hash_rng_next(rng), hash_rng_next(rng)), s)) continue;
    sum += (s.wi.z / kPi) / s.pdf;
  }
  EXPECT_NEAR(sum / n, 1.0, 0.01);
}

TEST(Brdf, GlossyAlbedoAgreesBetweenEstimatorsAndStaysBelowOne) {
  // The directional albedo of a white metal estimated two ways: by the BRDF's own importance
  // sampling (sum of weights) and by cosine sampling of eval. Both estimate the same integral,
  // so they must agree; single-scattering GGX loses energy, so it is below 1.
  vec3 wo = glm::normalize(vec3(0.0f, 0.3f, 1.0f));
  for (float roughness : {0.3f, 0.6f, 1.0f}) {
    Brdf metal = brdf_from_material(vec3(1.0f), 1.0f, roughness, false);
    Integrals cosine = integrate(metal, wo, 400000);
    HashRng rng = hash_rng(8, 8, 8);
    double sampled = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      BrdfSample s;
      if (brdf_sample(metal, wo, vec2(hash_rng_next(rng), hash_rng_next(rng)), s)) sampled += s.weight.x;
    }
    sampled /= n;
    EXPECT_NEAR(cosine.albedo.x, sampled, 0.02 * sampled) << roughness;
    EXPECT_LT(sampled, 1.0) << roughness;
    EXPECT_GT(sampled, 0.2) << roughness;
  }
}

TEST(Brdf, BelowTheHorizonIsBlack) {
  Brdf b = brdf_from_material(vec3(0.5f), 0.0f, 0.5f, false);
  EXPECT_EQ(brdf_eval(b, vec3(0, 0, 1), vec3(0, 0.5f, -0.5f)), vec3(0.0f));
  EXPECT_EQ(brdf_pdf(b, vec3(0, 0.5f, -0.5f), vec3(0, 0, 1)), 0.0f);
}

}  // namespace
}  // namespace sst
