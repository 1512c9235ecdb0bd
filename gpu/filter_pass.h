// The G-buffer-guided filters on the GPU (core/filter/filters.h has them on the CPU and documents
// the inputs): the same per-pixel kernels, one dispatch per pass, ping-ponging between buffers so
// that no dispatch reads what it writes. Each returns the images and the GPU time of its dispatches
// (timestamps), so that each filter is a timed stage.
#pragma once
#include "core/filter/filters.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

struct FilteredImage {
  Image image;
  double gpu_ms = 0.0;
};

struct SvgfSpatialImages : SvgfSpatialResult {
  double gpu_ms = 0.0;
};

FilteredImage atrous_filter(const VulkanContext& context, const Image& color, const Image& depth, const Image& normal,
                            const AtrousParams& params);
SvgfSpatialImages svgf_spatial(const VulkanContext& context, const Image& illumination, const Image& moments,
                               const Image& history_length, const Image& depth, const Image& normal,
                               const SvgfParams& params);
FilteredImage joint_bilateral_upsample(const VulkanContext& context, const Image& low, const Image& low_depth,
                                       const Image& low_normal, const Image& depth, const Image& normal,
                                       const UpsampleParams& params);

}  // namespace sst::gpu
