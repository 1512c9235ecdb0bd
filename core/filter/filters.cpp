#include "core/filter/filters.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <string>
#include <utility>

#include "core/filter/atrous_kernel.h"
#include "core/filter/svgf_kernel.h"
#include "core/filter/upsample_kernel.h"
#include "core/util/error.h"

namespace sst {
namespace {

// Calls write(x, y) for every pixel, in parallel tiles.
template <class F>
void for_each_pixel(int width, int height, const F& write) {
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, 16, 0, width, 64), [&](const tbb::blocked_range2d<int>& r) {
    for (int y = r.rows().begin(); y < r.rows().end(); ++y)
      for (int x = r.cols().begin(); x < r.cols().end(); ++x) write(x, y);
  });
}

// sst::Error unless `image` is width x height with `channels` channels; `what` names it.
void check_filter_image(const Image& image, int width, int height, int channels, const char* what) {
  if (image.width != width || image.height != height || image.channels != channels ||
      image.data.size() != image.pixel_count() * size_t(channels))
    throw Error(std::string("filter input ") + what + ": " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " with " + std::to_string(image.channels) + " channels, expected " +
                std::to_string(width) + "x" + std::to_string(height) + " with " + std::to_string(channels));
}

void check_gbuffer(int width, int height, const Image& depth, const Image& normal) {
  check_filter_image(depth, width, height, 1, "depth");
  check_filter_image(normal, width, height, 3, "normal");
}

}  // namespace

void check_atrous_inputs(const Image& color, const Image& depth, const Image& normal, const AtrousParams& params) {
  validate(params);
  check_filter_image(color, color.width, color.height, 3, "color");
  check_gbuffer(color.width, color.height, depth, normal);
}

void check_svgf_inputs(const Image& illumination, const Image& moments, const Image& history_length,
                       const Image& depth, const Image& normal, const SvgfParams& params) {
  validate(params);
  const int width = illumination.width, height = illumination.height;
  check_filter_image(illumination, width, height, 3, "illumination");
  check_filter_image(moments, width, height, 2, "moments");
  check_filter_image(history_length, width, height, 1, "history_length");
  check_gbuffer(width, height, depth, normal);
}

void check_upsample_inputs(const Image& low, const Image& low_depth, const Image& low_normal, const Image& depth,
                           const Image& normal, const UpsampleParams& params) {
  validate(params);
  const int width = depth.width, height = depth.height;
  check_gbuffer(width, height, depth, normal);
  auto fits = [](int low_size, int size) { return low_size >= 1 && low_size <= size; };
  if (!fits(low.width, width) || !fits(low.height, height))
    throw Error("upsample: the low-resolution image is " + std::to_string(low.width) + "x" +
                std::to_string(low.height) + ", not at most " + std::to_string(width) + "x" + std::to_string(height));
  check_filter_image(low, low.width, low.height, 3, "low-resolution color");
  check_gbuffer(low.width, low.height, low_depth, low_normal);
}

Image atrous_filter(const Image& color, const Image& depth, const Image& normal, const AtrousParams& params) {
  check_atrous_inputs(color, depth, normal, params);
  Image current = color, next(color.width, color.height, 3);
  FilterInputs fi;
  fi.depth = depth.data.data();
  fi.normal = normal.data.data();
  for (int level = 0; level < params.levels; ++level) {
    const glsl::AtrousPush push = atrous_push(params, color.width, color.height, level);
    fi.color = current.data.data();
    for_each_pixel(color.width, color.height, [&](int x, int y) { next.set_rgb(x, y, atrous_pixel(fi, push, x, y)); });
    std::swap(current, next);
  }
  return current;
}

SvgfSpatialResult svgf_spatial(const Image& illumination, const Image& moments, const Image& history_length,
                               const Image& depth, const Image& normal, const SvgfParams& params) {
  check_svgf_inputs(illumination, moments, history_length, depth, normal, params);
  const int width = illumination.width, height = illumination.height;
  FilterInputs fi;
  fi.depth = depth.data.data();
  fi.normal = normal.data.data();
  fi.moments = moments.data.data();
  fi.history = history_length.data.data();

  SvgfSpatialResult result;
  result.variance = Image(width, height, 1);
  const glsl::SvgfPush variance_push = svgf_push(params, width, height, SVGF_PASS_VARIANCE, 0);
  for_each_pixel(width, height,
                 [&](int x, int y) { result.variance.at(x, y, 0) = svgf_variance_pixel(fi, variance_push, x, y); });

  Image color = illumination, variance = result.variance;
  Image next_color(width, height, 3), next_variance(width, height, 1);
  result.level1 = illumination;
  for (int level = 0; level < params.levels; ++level) {
    const glsl::SvgfPush push = svgf_push(params, width, height, SVGF_PASS_ATROUS, level);
    fi.color = color.data.data();
    fi.variance = variance.data.data();
    for_each_pixel(width, height, [&](int x, int y) {
      vec4 v = svgf_atrous_pixel(fi, push, x, y);
      next_color.set_rgb(x, y, vec3(v.x, v.y, v.z));
      next_variance.at(x, y, 0) = v.w;
    });
    std::swap(color, next_color);
    std::swap(variance, next_variance);
    if (level == 0) result.level1 = color;
  }
  result.filtered = std::move(color);
  return result;
}

Image joint_bilateral_upsample(const Image& low, const Image& low_depth, const Image& low_normal, const Image& depth,
                               const Image& normal, const UpsampleParams& params) {
  check_upsample_inputs(low, low_depth, low_normal, depth, normal, params);
  const int width = depth.width, height = depth.height;
  FilterInputs fi;
  fi.color = low.data.data();
  fi.low_depth = low_depth.data.data();
  fi.low_normal = low_normal.data.data();
  fi.depth = depth.data.data();
  fi.normal = normal.data.data();
  const glsl::UpsamplePush push = upsample_push(params, width, height, low.width, low.height);
  Image out(width, height, 3);
  for_each_pixel(width, height, [&](int x, int y) { out.set_rgb(x, y, upsample_pixel(fi, push, x, y)); });
  return out;
}

vec3 albedo_divisor(vec3 albedo) { return filter_albedo_divisor(albedo); }

Image demodulate(const Image& light, const Image& albedo) {
  check_filter_image(light, light.width, light.height, 3, "light");
  check_filter_image(albedo, light.width, light.height, 3, "albedo");
  Image out(light.width, light.height, 3);
  for_each_pixel(light.width, light.height,
                 [&](int x, int y) { out.set_rgb(x, y, light.rgb(x, y) / filter_albedo_divisor(albedo.rgb(x, y))); });
  return out;
}

Image remodulate(const Image& illumination, const Image& albedo) {
  check_filter_image(illumination, illumination.width, illumination.height, 3, "illumination");
  check_filter_image(albedo, illumination.width, illumination.height, 3, "albedo");
  Image out(illumination.width, illumination.height, 3);
  for_each_pixel(illumination.width, illumination.height, [&](int x, int y) {
    out.set_rgb(x, y, illumination.rgb(x, y) * filter_albedo_divisor(albedo.rgb(x, y)));
  });
  return out;
}

}  // namespace sst
