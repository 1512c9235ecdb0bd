#include "gpu/filter_pass.h"

#include <memory>
#include <utility>

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"

namespace sst::gpu {
namespace {

std::unique_ptr<GpuBuffer> upload_image(const VulkanContext& context, const Image& image, const char* what) {
  return upload_buffer(context, image.data, what);
}

std::unique_ptr<GpuBuffer> image_buffer(const VulkanContext& context, int width, int height, int channels,
                                        const char* what) {
  return make_buffer(context, size_t(width) * size_t(height) * size_t(channels), sizeof(float), what);
}

Image download_image(const GpuBuffer& buffer, int width, int height, int channels) {
  Image image(width, height, channels);
  buffer.download(std::span<float>(image.data));
  return image;
}

uint32_t groups(int size) { return (uint32_t(size) + 7u) / 8u; }

}  // namespace

FilteredImage atrous_filter(const VulkanContext& context, const Image& color, const Image& depth, const Image& normal,
                            const AtrousParams& params) {
  check_atrous_inputs(color, depth, normal, params);
  const int width = color.width, height = color.height;
  FilteredImage result;
  if (params.levels == 0 || color.pixel_count() == 0) {
    result.image = color;
    return result;
  }
  auto depth_buffer = upload_image(context, depth, "a-trous depth");
  auto normal_buffer = upload_image(context, normal, "a-trous normal");
  auto current = upload_image(context, color, "a-trous colour");
  auto next = image_buffer(context, width, height, 3, "a-trous colour");
  ComputePipeline pipeline(context, "filter_atrous", 4, sizeof(glsl::AtrousPush));
  for (int level = 0; level < params.levels; ++level) {
    const glsl::AtrousPush push = atrous_push(params, width, height, level);
    result.gpu_ms += pipeline.dispatch({current.get(), depth_buffer.get(), normal_buffer.get(), next.get()}, &push,
                                       groups(width), groups(height));
    std::swap(current, next);
  }
  result.image = download_image(*current, width, height, 3);
  return result;
}

SvgfSpatialImages svgf_spatial(const VulkanContext& context, const Image& illumination, const Image& moments,
                               const Image& history_length, const Image& depth, const Image& normal,
                               const SvgfParams& params) {
  check_svgf_inputs(illumination, moments, history_length, depth, normal, params);
  const int width = illumination.width, height = illumination.height;
  SvgfSpatialImages result;
  if (illumination.pixel_count() == 0) {
    result.filtered = result.level1 = illumination;
    result.variance = Image(width, height, 1);
    return result;
  }
  auto moments_buffer = upload_image(context, moments, "SVGF moments");
  auto history_buffer = upload_image(context, history_length, "SVGF history length");
  auto depth_buffer = upload_image(context, depth, "SVGF depth");
  auto normal_buffer = upload_image(context, normal, "SVGF normal");
  auto color = upload_image(context, illumination, "SVGF illumination");
  auto next_color = image_buffer(context, width, height, 3, "SVGF illumination");
  auto variance = image_buffer(context, width, height, 1, "SVGF variance");
  auto next_variance = image_buffer(context, width, height, 1, "SVGF variance");
  ComputePipeline pipeline(context, "filter_svgf", 8, sizeof(glsl::SvgfPush));
  auto run = [&](const glsl::SvgfPush& push) {
    result.gpu_ms += pipeline.dispatch({color.get(), variance.get(), moments_buffer.get(), history_buffer.get(),
                                        depth_buffer.get(), normal_buffer.get(), next_color.get(), next_variance.get()},
                                       &push, groups(width), groups(height));
  };
  run(svgf_push(params, width, height, SVGF_PASS_VARIANCE, 0));
  std::swap(variance, next_variance);
  result.variance = download_image(*variance, width, height, 1);
  result.level1 = illumination;
  for (int level = 0; level < params.levels; ++level) {
    run(svgf_push(params, width, height, SVGF_PASS_ATROUS, level));
    std::swap(color, next_color);
    std::swap(variance, next_variance);
    if (level == 0) result.level1 = download_image(*color, width, height, 3);
  }
  result.filtered = download_image(*color, width, height, 3);
  return result;
}

FilteredImage joint_bilateral_upsample(const VulkanContext& context, const Image& low, const Image& low_depth,
                                       const Image& low_normal, const Image& depth, const Image& normal,
                                       const UpsampleParams& params) {
  check_upsample_inputs(low, low_depth, low_normal, depth, normal, params);
  const int width = depth.width, height = depth.height;
  FilteredImage result;
  if (depth.pixel_count() == 0) {
    result.image = Image(width, height, 3);
    return result;
  }
  auto low_buffer = upload_image(context, low, "upsampling low-resolution colour");
  auto low_depth_buffer = upload_image(context, low_depth, "upsampling low-resolution depth");
  auto low_normal_buffer = upload_image(context, low_normal, "upsampling low-resolution normal");
  auto depth_buffer = upload_image(context, depth, "upsampling depth");
  auto normal_buffer = upload_image(context, normal, "upsampling normal");
  auto out = image_buffer(context, width, height, 3, "upsampled colour");
  ComputePipeline pipeline(context, "filter_upsample", 6, sizeof(glsl::UpsamplePush));
  const glsl::UpsamplePush push = upsample_push(params, width, height, low.width, low.height);
  result.gpu_ms = pipeline.dispatch({low_buffer.get(), low_depth_buffer.get(), low_normal_buffer.get(),
                                     depth_buffer.get(), normal_buffer.get(), out.get()},
                                    &push, groups(width), groups(height));
  result.image = download_image(*out, width, height, 3);
  return result;
}

}  // namespace sst::gpu
