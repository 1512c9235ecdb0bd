#include "core/filter/filter_params.h"

#include <cmath>
#include <string>

#include "core/util/error.h"

namespace sst {
namespace {

// Level counts beyond this would space taps farther apart than any image is wide.
constexpr int kMaxLevels = 16;

void check_levels(const char* filter, int levels) {
  if (levels < 0 || levels > kMaxLevels)
    throw Error(std::string(filter) + ": levels = " + std::to_string(levels) + " is outside 0.." +
                std::to_string(kMaxLevels));
}

void check_positive(const char* filter, const char* name, float value) {
  if (!(value > 0.0f) || !std::isfinite(value))
    throw Error(std::string(filter) + ": " + name + " = " + std::to_string(value) + " must be positive and finite");
}

}  // namespace

void validate(const AtrousParams& params) {
  check_levels("atrous", params.levels);
  check_positive("atrous", "sigma_color", params.sigma_color);
  check_positive("atrous", "sigma_normal", params.sigma_normal);
  check_positive("atrous", "sigma_depth", params.sigma_depth);
}

void validate(const SvgfParams& params) {
  check_levels("svgf", params.levels);
  check_positive("svgf", "sigma_z", params.sigma_z);
  // sigma_n = 0 is allowed: normals then do not stop the filter (x^0 = 1).
  if (!(params.sigma_n >= 0.0f) || !std::isfinite(params.sigma_n))
    throw Error("svgf: sigma_n = " + std::to_string(params.sigma_n) + " must be >= 0 and finite");
  check_positive("svgf", "sigma_l", params.sigma_l);
  if (params.min_history < 0) throw Error("svgf: min_history = " + std::to_string(params.min_history) + " must be >= 0");
}

void validate(const UpsampleParams& params) {
  if (!(params.n_min >= -1.0f && params.n_min <= 1.0f))
    throw Error("upsample: n_min = " + std::to_string(params.n_min) + " is outside -1..1");
  check_positive("upsample", "d_max", params.d_max);
}

glsl::AtrousPush atrous_push(const AtrousParams& params, int width, int height, int level) {
  glsl::AtrousPush p{};
  p.width = uint32_t(width);
  p.height = uint32_t(height);
  p.step = 1u << level;
  const float step = float(p.step);
  p.inv_color = step / (params.sigma_color * params.sigma_color);
  p.inv_normal = 1.0f / (params.sigma_normal * params.sigma_normal * step * step);
  p.inv_depth = 1.0f / (params.sigma_depth * params.sigma_depth);
  return p;
}

glsl::SvgfPush svgf_push(const SvgfParams& params, int width, int height, uint32_t pass, int level) {
  glsl::SvgfPush p{};
  p.width = uint32_t(width);
  p.height = uint32_t(height);
  p.step = 1u << level;
  p.pass = pass;
  p.sigma_z = params.sigma_z;
  p.sigma_n = params.sigma_n;
  p.sigma_l = params.sigma_l;
  p.min_history = float(params.min_history);
  return p;
}

glsl::UpsamplePush upsample_push(const UpsampleParams& params, int width, int height, int low_width, int low_height) {
  glsl::UpsamplePush p{};
  p.width = uint32_t(width);
  p.height = uint32_t(height);
  p.low_width = uint32_t(low_width);
  p.low_height = uint32_t(low_height);
  p.n_min = params.n_min;
  p.d_max = params.d_max;
  return p;
}

}  // namespace sst
