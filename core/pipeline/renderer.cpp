#include "core/pipeline/renderer.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <memory>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/pipeline/backend.h"
#include "core/render/camera.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/render_record.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_render_context.h"
#include "gpu/vulkan_method.h"
#endif

namespace sst {

double frame_ms(const RenderResult& result) {
  double ms = 0.0;
  for (const auto& [stage, t] : result.timer.stages())
    if (stage != "accel_build" && stage != "light_setup" && stage != "gpu_setup" && stage != "shader_compile") ms += t;
  return ms;
}

RenderResult render_frame(const Scene& scene, const RenderOptions& options, const nlohmann::json& method_params,
                          bool quiet) {
  RenderResult result;
  result.options = options;
  validate(result.options);
  // The backend that runs ("auto" becomes a concrete one; "vulkan" without a device fails with one line).
  std::string backend_note;
  result.options.backend = resolve_backend(options.backend, options.device, &backend_note);
  if (!backend_note.empty() && !quiet) std::fprintf(stderr, "note: %s\n", backend_note.c_str());
  // Create the method first: a bad parameter fails before any expensive work.
  std::unique_ptr<Method> method = create_method(options.method, method_params);
  result.method_params = method->params();

  std::unique_ptr<tbb::global_control> threads;
  if (options.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

  const Camera& camera = select_camera(scene, options.camera);
  resolve_resolution(camera, result.options.width, result.options.height);
  validate(result.options);
  // A Vulkan render traces every ray through the flat BVH, also those the CPU traces for it (the
  // guide pixels of rtslc's and the hybrid's cuts), so that nothing in it depends on Embree.
  if (result.options.backend == "vulkan") result.options.accel = "flat";
  auto accel = result.timer.time("accel_build",
                                 [&] { return std::make_unique<EmbreeAccel>(scene, result.options.accel == "flat"); });
  auto lights = result.timer.time("light_setup", [&] { return std::make_unique<LightSampler>(scene); });
  PinholeCamera pinhole(camera, result.options.width, result.options.height);
  RenderContext context{scene, *accel, *lights, pinhole, result.options, result.options.width, result.options.height, quiet};
  result.device = cpu_device_record(result.options);
  if (result.options.backend == "vulkan") {
#ifdef SST_HAVE_VULKAN
    // The method's Vulkan side renders with both the CPU structures above (VPL methods build some
    // trees and their cuts on the CPU) and the scene uploaded to the device.
    std::unique_ptr<gpu::VulkanMethod> vulkan_method = gpu::make_vulkan_method(*method, options.method);
    auto gpu = result.timer.time("gpu_setup", [&] {
      return std::make_unique<gpu::GpuRenderContext>(result.options.device, scene, *lights, *accel->flat_bvh());
    });
    result.device = vulkan_device_record(gpu->vulkan().info(), gpu->describe());
    result.frame = vulkan_method->render(context, *gpu, result.timer);
    return result;
#endif
  }
  result.frame = method->render(context, result.timer);
  return result;
}

}  // namespace sst
