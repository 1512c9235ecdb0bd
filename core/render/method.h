// A rendering method (pt, or one of the many-light methods) renders one frame of a prepared scene
// on the CPU. Methods are created by name through the registry (core/pipeline/method_registry.h),
// which is the one place a new method is added; sst-render, sst-eval and the tests reach it there.
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
};

class Method {
 public:
  virtual ~Method() = default;
  // Renders the frame, timing its stages into `timer` (names: "render", or the method's stages).
  // A method's Vulkan side is an object of its own in gpu/ (gpu/vulkan_method.h).
  virtual FrameOutput render(const RenderContext& context, StageTimer& timer) = 0;
  // Every parameter in effect, for the JSON record.
  virtual nlohmann::json params() const = 0;
};

}  // namespace sst
