#include "gpu/gbuffer_pass.h"

#include "core/render/camera.h"

namespace sst::gpu {

GBufferImages render_gbuffer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                             const PinholeCamera& camera, int width, int height, uint32_t seed, int spp) {
  glsl::ViewParams view = view_params(camera, width, height, seed);
  view.spp = uint32_t(spp);

  const size_t pixels = size_t(width) * size_t(height);
  GpuBuffer out(context, pixels * sizeof(glsl::GBufferTexel));
  std::vector<const GpuBuffer*> buffers = scene.buffers();
  for (const GpuBuffer* buffer : bvh.buffers()) buffers.push_back(buffer);
  buffers.push_back(&out);
  ComputePipeline pipeline(context, "gbuffer", uint32_t(buffers.size()), sizeof view);
  GBufferImages images;
  images.gpu_ms = pipeline.dispatch(buffers, &view, (uint32_t(width) + 7) / 8, (uint32_t(height) + 7) / 8);

  std::vector<glsl::GBufferTexel> texels(pixels);
  out.download(std::span<glsl::GBufferTexel>(texels));
  images.albedo = Image(width, height);
  images.normal = Image(width, height);
  images.emission = Image(width, height);
  images.depth = Image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glsl::GBufferTexel& t = texels[size_t(y) * width + x];
      images.albedo.set_rgb(x, y, t.albedo);
      images.normal.set_rgb(x, y, t.normal);
      images.emission.set_rgb(x, y, t.emission);
      images.depth.at(x, y, 0) = t.depth;
    }
  return images;
}

}  // namespace sst::gpu
