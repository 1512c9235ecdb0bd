// The Vulkan side of a method: it renders the frame of the method's CPU object on the GPU, with the
// same parameters, random numbers and outputs. Kept apart from the method's class, so that core
// builds and tests without Vulkan; the pipeline (core/pipeline/renderer.cpp) creates one when the
// backend is vulkan.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/render/frame.h"
#include "core/render/method.h"
#include "core/util/stage_timer.h"

namespace sst::gpu {

class GpuRenderContext;

class VulkanMethod {
 public:
  virtual ~VulkanMethod() = default;
  // `context` holds the frame's CPU-side inputs (scene, accel, lights, camera, options), `gpu` the
  // device and the scene, BVH and lights uploaded to it.
  virtual FrameOutput render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) = 0;
  // Called before the device context it rendered with is destroyed (the pipeline rebuilds it when
  // lights or geometry move): whatever the method keeps on that device must go now.
  virtual void release_device() {}
  // Method::save_history and restore_history for what the Vulkan side keeps from frame to frame.
  virtual std::vector<uint8_t> save_history() const { return {}; }
  virtual void restore_history(std::span<const uint8_t> bytes, bool posed) {}
};

// The Vulkan side of `method`, which it refers to and which must outlive it. Throws sst::Error
// naming `name` when the method has no Vulkan port.
std::unique_ptr<VulkanMethod> make_vulkan_method(Method& method, const std::string& name);

}  // namespace sst::gpu
