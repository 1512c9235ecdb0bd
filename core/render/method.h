// A rendering method (pt, or one of the many-light methods) renders one frame of a prepared scene
// on the CPU. Methods are created by name through the registry (core/pipeline/method_registry.h),
// which lists each method's MethodInfo; sst-render, sst-eval and the tests reach them there.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/camera.h"
#include "core/render/frame.h"
#include "core/render/render_options.h"
#include "core/scene/scene.h"
#include "core/util/params.h"
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
  // The frame's index in its sequence (0 for a single frame), for methods that spread work over
  // frames (rtslc's interleaved sampling takes another slot of each tile every frame).
  int frame = 0;
};

class Method {
 public:
  virtual ~Method() = default;
  // Renders the frame, timing its stages into `timer` (names: "render", or the method's stages).
  // A method's Vulkan side is an object of its own in gpu/ (gpu/vulkan_method.h).
  virtual FrameOutput render(const RenderContext& context, StageTimer& timer) = 0;
  // Every parameter in effect, for the JSON record.
  virtual nlohmann::json params() const = 0;
  // The scene was posed again (geometry or lights moved, FrameRenderer::prepare): state a method
  // keeps from frame to frame about the old pose is dropped here, as its Vulkan side's is with the
  // device (VulkanMethod::release_device), so that both backends go on alike.
  virtual void scene_posed() {}
  // The state a method keeps from frame to frame, as bytes only it reads (empty: none), for
  // sequence checkpoints of resumable methods (MethodInfo::resumable); restore_history reads them
  // back into a new method before its next frame, `posed` when the scene was posed anew since they
  // were saved. A method with state of its own is resumable only if these two carry all of it.
  virtual std::vector<uint8_t> save_history() const { return {}; }
  virtual void restore_history(std::span<const uint8_t> bytes, bool posed) {}
};

// A method as the registry lists it: name -> description, parameter table, factory. Each method
// defines its own in its folder (<name>_method_info()); the CLIs build their flags from the tables.
struct MethodInfo {
  std::string name;
  std::string description;
  std::vector<ParamInfo> params;
  // Builds the method from its parameters; unknown keys are an error naming the key.
  std::function<std::unique_ptr<Method>(const nlohmann::json& params)> create;
  // Whether an interrupted sequence can continue from its checkpoint (the pipeline's SequenceState
  // with the method's save_history); false for a method that carries state of its own from frame
  // to frame that save_history does not hold, whose resumed run would start that state over.
  bool resumable = true;
};

// The MethodInfo of a method whose parameters P (with visit()) are read from JSON and handed to
// `make(P)`.
template <class P, class Make>
MethodInfo method_info(const char* name, const char* description, Make make) {
  return {name, description, param_table<P>(), [name, make](const nlohmann::json& j) -> std::unique_ptr<Method> {
            P params;
            params_from_json(params, j, std::string("method '") + name + "'");
            return make(params);
          }};
}

}  // namespace sst
