#include "core/metrics/error_map.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/metrics/same_shape.h"

namespace sst {
namespace {

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.0f; }

// matplotlib's inferno sampled at 17 evenly spaced points (sRGB values).
constexpr std::array<std::array<float, 3>, 17> kInferno{{
    {0.001462f, 0.000466f, 0.013866f},
    {0.042253f, 0.028139f, 0.141141f},
    {0.129285f, 0.047293f, 0.290788f},
    {0.238273f, 0.036621f, 0.396353f},
    {0.341500f, 0.062325f, 0.429425f},
    {0.441207f, 0.099338f, 0.431594f},
    {0.540920f, 0.134729f, 0.415123f},
    {0.640135f, 0.171438f, 0.381065f},
    {0.735683f, 0.215906f, 0.330245f},
    {0.822386f, 0.275197f, 0.266085f},
    {0.894305f, 0.353399f, 0.193584f},
    {0.946965f, 0.449191f, 0.115272f},
    {0.978422f, 0.557937f, 0.034931f},
    {0.987874f, 0.675267f, 0.065257f},
    {0.974638f, 0.797692f, 0.206332f},
    {0.947594f, 0.917399f, 0.410665f},
    {0.988362f, 0.998364f, 0.644924f},
}};

vec3 table_entry(size_t i) { return {kInferno[i][0], kInferno[i][1], kInferno[i][2]}; }

}  // namespace

vec3 inferno(float t) {
  const float s = std::clamp(finite_or_zero(t), 0.0f, 1.0f) * float(kInferno.size() - 1);
  const size_t i = std::min(size_t(s), kInferno.size() - 2);
  return glm::mix(table_entry(i), table_entry(i + 1), s - float(i));
}

Image relative_error_image(const Image& test, const Image& reference) {
  require_same_shape(test, reference);
  Image out(test.width, test.height, 1);
  const int nc = test.channels;
  for (size_t p = 0; p < out.pixel_count(); ++p) {
    double diff = 0.0, ref = 0.0;
    for (int c = 0; c < nc; ++c) {
      const double t = finite_or_zero(test.data[p * nc + c]), r = finite_or_zero(reference.data[p * nc + c]);
      diff += std::abs(t - r);
      ref += std::abs(r);
    }
    out.data[p] = float((diff / nc) / (ref / nc + 0.01));
  }
  return out;
}

Image squared_error_image(const Image& test, const Image& reference) {
  require_same_shape(test, reference);
  Image out(test.width, test.height, test.channels);
  for (size_t i = 0; i < out.data.size(); ++i) {
    const float d = finite_or_zero(test.data[i]) - finite_or_zero(reference.data[i]);
    out.data[i] = d * d;
  }
  return out;
}

Image inferno_image(const Image& values, float max_value) {
  const float scale = max_value > 0.0f ? 1.0f / max_value : 1.0f;
  Image out(values.width, values.height, 3);
  for (size_t p = 0; p < values.pixel_count(); ++p) {
    const vec3 c = inferno(values.data[p * values.channels] * scale);
    for (int k = 0; k < 3; ++k) out.data[p * 3 + k] = srgb_decode(c[k]);
  }
  return out;
}

Image error_heatmap(const Image& test, const Image& reference, float max_error) {
  return inferno_image(relative_error_image(test, reference), max_error);
}

}  // namespace sst
