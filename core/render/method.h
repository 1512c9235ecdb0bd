// A rendering method (pt, and the many-light samplers to come) renders one frame of a prepared
// scene. Methods are created by name through the registry (method_registry.h), which is the one
// place a new method is added; sst-render, sst-eval and the tests reach it from there.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/camera.h"
#include "core/render/frame.h"
#include "core/render/render_options.h"
#include "core/scene/scene.h"
#include "core/util/stage_timer.h"

namespace sst::gpu {
class GpuRenderContext;  // gpu/gpu_render_context.h: the device and the scene on it
}

namespace sst {

class Progress;

// Everything a method may read while rendering: built once per scene and camera.
struct RenderContext {
  const Scene& scene;
  const EmbreeAccel& accel;
  const LightSampler& lights;
  const PinholeCamera& camera;
  const RenderOptions& options;
  int width, height;
  bool quiet = false;
  // The Vulkan device and the scene uploaded to it; null on the CPU backend.
  const gpu::GpuRenderContext* gpu = nullptr;
};

class Method {
 public:
  virtual ~Method() = default;
  // Renders the frame, timing its stages into `timer` (names: "render", or the method's stages).
  virtual FrameOutput render(const RenderContext& context, StageTimer& timer) = 0;
  // The same frame on the Vulkan backend (context.gpu is set): the same parameters, random numbers
  // and outputs. A method without a Vulkan port keeps this default, which throws sst::Error.
  virtual FrameOutput render_vulkan(const RenderContext& context, StageTimer& timer);
  // Every parameter in effect, for the JSON record.
  virtual nlohmann::json params() const = 0;
};

}  // namespace sst
