// Renders one frame of a loaded scene: acceleration structure, lights, camera, then the method.
// Shared by sst-render, sst-eval and the tests, so all of them run exactly the same pipeline.
#pragma once
#include <nlohmann/json.hpp>

#include "core/render/frame.h"
#include "core/render/render_options.h"
#include "core/scene/scene.h"
#include "core/util/stage_timer.h"

namespace sst {

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

RenderResult render_frame(const Scene& scene, const RenderOptions& options, const nlohmann::json& method_params,
                          bool quiet = true);

}  // namespace sst
