// Renders frames of a loaded scene: acceleration structure, lights, camera, then the method.
// Shared by sst-render, sst-eval and the tests, so all of them run exactly the same pipeline.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/pipeline/sequence_state.h"
#include "core/render/frame.h"
#include "core/render/method.h"
#include "core/render/render_options.h"
#include "core/scene/scene.h"
#include "core/util/stage_timer.h"

namespace sst {
struct RestirHistory;
namespace gpu {
class GpuRenderContext;
class VulkanMethod;
struct RestirPipelines;
struct GpuRestirHistory;
}  // namespace gpu

struct RenderResult {
  FrameOutput frame;
  RenderOptions options;           // as resolved (width and height filled in)
  nlohmann::json method_params;    // every parameter of the method in effect
  StageTimer timer;                // "accel_build", "light_setup", ["gpu_setup",] then the method's stages
  nlohmann::json device;           // where it ran (device_record in render_record.h)
};

// The time of the frame itself: every stage but the per-scene and per-program setup that an
// application pays once (accel_build, light_setup, gpu_setup, shader_compile).
double frame_ms(const RenderResult& result);

// One method on one backend, rendering frame after frame of a scene whose pose may change between
// them. What does not depend on the pose (the method, the device) is made once; what does (the
// acceleration structure, the lights, their uploads) is rebuilt by prepare().
class FrameRenderer {
 public:
  // Validates the options and creates the method; a bad parameter fails before any expensive work.
  FrameRenderer(const RenderOptions& options, const nlohmann::json& method_params, bool quiet);
  ~FrameRenderer();

  // Builds the acceleration structure, light sampler and device uploads of `scene` as posed now,
  // timing them into `timer`; again whenever posing moved geometry or lights.
  void prepare(const Scene& scene, StageTimer& timer);
  // One frame of the prepared scene seen by `camera` (as posed), at `width` x `height` (0: the
  // options'), with `seed`. The result's timer holds the method's stages.
  // `frame`: the frame's index in its sequence (RenderContext::frame). `direct_light` false: the
  // caller uses the frame's indirect light only (a half-resolution GI frame), so ReSTIR DI's pass
  // (--direct-sampler restir) is skipped and its history left to the frames that use it.
  RenderResult render(const Scene& scene, const Camera& camera, uint32_t seed, int width = 0, int height = 0,
                      int frame = 0, bool direct_light = true);
  // The same frame's direct light and first-hit AOVs only (the path tracer with no bounce: what
  // every method's direct pass computes), for a frame whose indirect light is rendered apart.
  RenderResult render_direct(const Scene& scene, const Camera& camera, uint32_t seed);

  // What frames hand to the next besides the image-space history: ReSTIR DI's history and the
  // method's state, as bytes (SequenceState's `direct_history`, `method_history`). restore after
  // prepare(), `posed` when the scene was posed anew since they were saved.
  void save_histories(SequenceState& state) const;
  void restore_histories(const SequenceState& state, bool posed);

  const RenderOptions& options() const { return options_; }  // resolved: backend, accel
  const EmbreeAccel& accel() const { return *accel_; }
  // The device and uploads of a Vulkan render (null on the CPU backend).
  const gpu::GpuRenderContext* gpu() const { return gpu_.get(); }

 private:
  RenderResult render_with(Method& method, gpu::VulkanMethod* vulkan_method, const std::string& method_name,
                           const Scene& scene, const Camera& camera, uint32_t seed, int width, int height, int frame,
                           bool direct_light);

  RenderOptions options_;
  bool quiet_;
  std::unique_ptr<Method> method_;
  std::unique_ptr<Method> direct_;  // pt with max_bounces 0, made on first use
  std::unique_ptr<EmbreeAccel> accel_;
  std::unique_ptr<LightSampler> lights_;
  std::unique_ptr<gpu::GpuRenderContext> gpu_;
  std::string gpu_accel_ = "flat";  // GpuRenderContext's accel: flat, rayquery or auto
  std::unique_ptr<gpu::VulkanMethod> vulkan_method_, vulkan_direct_;
  // --direct-sampler restir: the Vulkan pipelines, and each backend's history for temporal reuse.
  std::unique_ptr<gpu::RestirPipelines> restir_pipelines_;
  std::unique_ptr<gpu::GpuRestirHistory> gpu_restir_history_;
  std::unique_ptr<RestirHistory> restir_history_;
  nlohmann::json device_;
  std::unique_ptr<class ThreadLimit> threads_;
};

// One frame with a scene's selected camera (options.camera): a FrameRenderer prepared and run once.
RenderResult render_frame(const Scene& scene, const RenderOptions& options, const nlohmann::json& method_params,
                          bool quiet = true);

}  // namespace sst
