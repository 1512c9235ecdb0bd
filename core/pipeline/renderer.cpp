#include "core/pipeline/renderer.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <memory>

#include "core/pipeline/backend.h"
#include "core/render/camera.h"
#include "core/restir/restir_di.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/render_record.h"
#include "core/util/error.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_render_context.h"
#include "gpu/restir_pass.h"
#include "gpu/vulkan_method.h"
#else
namespace sst::gpu {
// Never made without Vulkan; complete types let FrameRenderer's unique_ptrs to them be destroyed.
class GpuRenderContext {};
class VulkanMethod {};
struct RestirPipelines {};
struct GpuRestirHistory {};
}  // namespace sst::gpu
#endif

namespace sst {

// The thread count a renderer was asked for, in force while it lives.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) : control_(tbb::global_control::max_allowed_parallelism, size_t(threads)) {}

 private:
  tbb::global_control control_;
};

double frame_ms(const RenderResult& result) {
  double ms = 0.0;
  for (const auto& [stage, t] : result.timer.stages())
    if (stage != "accel_build" && stage != "light_setup" && stage != "gpu_setup" && stage != "shader_compile") ms += t;
  return ms;
}

FrameRenderer::FrameRenderer(const RenderOptions& options, const nlohmann::json& method_params, bool quiet)
    : options_(options), quiet_(quiet) {
  validate(options_);
  // The backend that runs ("auto" becomes a concrete one; "vulkan" without a device fails with one line).
  std::string backend_note;
  options_.backend = resolve_backend(options.backend, options.device, &backend_note);
  if (!backend_note.empty() && !quiet) std::fprintf(stderr, "note: %s\n", backend_note.c_str());
  method_ = create_method(options.method, method_params);
  if (options.threads > 0) threads_ = std::make_unique<ThreadLimit>(options.threads);
  if (options_.accel == "rayquery" && options_.backend != "vulkan")
    throw Error("--accel rayquery needs the Vulkan backend (--backend vulkan)");
  // The rays a Vulkan render's CPU side traces (the guide pixels of rtslc's and the hybrid's cuts)
  // go through the flat BVH, so that nothing in it depends on Embree; its shaders trace that BVH
  // or the device's acceleration structures (gpu_accel_, resolved when the device is open).
  if (options_.backend == "vulkan") {
    gpu_accel_ = options_.accel == "embree" ? "auto" : options_.accel;
    options_.accel = "flat";
  }
  device_ = cpu_device_record(options_);
#ifdef SST_HAVE_VULKAN
  if (options_.backend == "vulkan") vulkan_method_ = gpu::make_vulkan_method(*method_, options.method);
#endif
}

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::prepare(const Scene& scene, StageTimer& timer) {
  check_coordinates(scene);  // before Embree sees a vertex it cannot bound
  accel_ = timer.time("accel_build", [&] { return std::make_unique<EmbreeAccel>(scene, options_.accel != "embree"); });
  // ReSTIR's histories name lights and points of the previous pose: their next temporal pass
  // evaluates them in this one. On Vulkan they live on the device made again below, so they wait
  // on the host meanwhile.
  if (restir_history_) restir_history_->posed = true;
  method_->scene_posed();
  lights_ = timer.time("light_setup", [&] {
    return std::make_unique<LightSampler>(scene, parse_light_sampler(options_.light_sampler),
                                          parse_emitter_tree_build(options_.light_tree),
                                          parse_emitter_distance(options_.light_tree_distance));
  });
#ifdef SST_HAVE_VULKAN
  if (options_.backend == "vulkan") {
    // The method's Vulkan side renders with both the CPU structures above (VPL methods build some
    // trees and their cuts on the CPU) and the scene uploaded to the device.
    if (vulkan_method_) vulkan_method_->release_device();
    restir_pipelines_.reset();
    if (gpu_restir_history_) gpu::park_restir_history(*gpu_restir_history_);
    gpu_.reset();
    gpu_ = timer.time("gpu_setup", [&] {
      return std::make_unique<gpu::GpuRenderContext>(options_.device, scene, *lights_, *accel_->flat_bvh(), gpu_accel_);
    });
    options_.accel = gpu_->accel();  // what the record reports
    device_ = vulkan_device_record(gpu_->vulkan().info(), gpu_->describe());
  }
#endif
}

RenderResult FrameRenderer::render(const Scene& scene, const Camera& camera, uint32_t seed, int width, int height,
                                   int frame, bool direct_light) {
  return render_with(*method_, vulkan_method_.get(), options_.method, scene, camera, seed, width, height, frame,
                     direct_light);
}

RenderResult FrameRenderer::render_direct(const Scene& scene, const Camera& camera, uint32_t seed) {
  if (!direct_) {
    direct_ = create_method("pt", {{"max_bounces", 0}});
#ifdef SST_HAVE_VULKAN
    if (options_.backend == "vulkan") vulkan_direct_ = gpu::make_vulkan_method(*direct_, "pt");
#endif
  }
  return render_with(*direct_, vulkan_direct_.get(), "pt", scene, camera, seed, 0, 0, 0, true);
}

RenderResult FrameRenderer::render_with(Method& method, gpu::VulkanMethod* vulkan_method, const std::string& name,
                                        const Scene& scene, const Camera& camera, uint32_t seed, int width,
                                        int height, int frame, bool direct_light) {
  if (!accel_) throw Error("FrameRenderer::render before prepare");
  check_coordinates(camera, scene.source);  // before any ray starts there
  RenderResult result;
  result.options = options_;
  result.options.method = name;
  result.options.seed = seed;
  if (width > 0 || height > 0) {
    result.options.width = width;
    result.options.height = height;
  }
  resolve_resolution(camera, result.options.width, result.options.height);
  validate(result.options);
  result.method_params = method.params();
  result.device = device_;
  PinholeCamera pinhole(camera, result.options.width, result.options.height);
  RenderContext context{scene,          *accel_,         *lights_, pinhole, result.options, result.options.width,
                        result.options.height, quiet_,   frame};
  // Under ReSTIR DI the method's paths gathered no direct light at their first hits
  // (restir_direct): the ReSTIR pass adds it, on the method's backend.
#ifdef SST_HAVE_VULKAN
  if (vulkan_method) {
    result.frame = vulkan_method->render(context, *gpu_, result.timer);
    if (direct_light && restir_direct(result.options)) {
      if (!restir_pipelines_)
        restir_pipelines_ = result.timer.time("shader_compile", [&] { return gpu::make_restir_pipelines(*gpu_); });
      if (!gpu_restir_history_) gpu_restir_history_ = std::make_unique<gpu::GpuRestirHistory>();
      gpu::add_restir_direct(context, *gpu_, *restir_pipelines_, result.timer, result.frame, *gpu_restir_history_);
    }
    return result;
  }
#else
  (void)vulkan_method;
#endif
  result.frame = method.render(context, result.timer);
  if (direct_light && restir_direct(result.options)) {
    if (!restir_history_) restir_history_ = std::make_unique<RestirHistory>();
    add_restir_direct(context, result.timer, result.frame, *restir_history_);
  }
  return result;
}

void FrameRenderer::save_histories(SequenceState& state) const {
#ifdef SST_HAVE_VULKAN
  if (vulkan_method_) {
    state.direct_history =
        gpu_restir_history_ ? restir_history_bytes(gpu::download_restir_history(*gpu_restir_history_)) : std::vector<uint8_t>{};
    state.method_history = vulkan_method_->save_history();
    return;
  }
#endif
  state.direct_history = restir_history_ ? restir_history_bytes(*restir_history_) : std::vector<uint8_t>{};
  state.method_history = method_->save_history();
}

void FrameRenderer::restore_histories(const SequenceState& state, bool posed) {
#ifdef SST_HAVE_VULKAN
  if (vulkan_method_) {
    if (!gpu_restir_history_) gpu_restir_history_ = std::make_unique<gpu::GpuRestirHistory>();
    gpu::restore_restir_history(*gpu_restir_history_, restir_history_from_bytes(state.direct_history), posed);
    vulkan_method_->restore_history(state.method_history, posed);
    return;
  }
#endif
  restir_history_ = std::make_unique<RestirHistory>(restir_history_from_bytes(state.direct_history));
  restir_history_->posed = posed;
  method_->restore_history(state.method_history, posed);
}

RenderResult render_frame(const Scene& scene, const RenderOptions& options, const nlohmann::json& method_params,
                          bool quiet) {
  FrameRenderer renderer(options, method_params, quiet);
  StageTimer setup;
  renderer.prepare(scene, setup);
  RenderResult result = renderer.render(scene, select_camera(scene, options.camera), options.seed);
  StageTimer timer = setup;
  for (const auto& [stage, ms] : result.timer.stages()) timer.add(stage, ms);
  result.timer = timer;
  return result;
}

}  // namespace sst
