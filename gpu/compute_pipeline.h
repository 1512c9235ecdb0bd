// One compute shader as a pipeline: its storage buffers are bindings 0..n-1 of set 0, its
// parameters a push-constant block. dispatch() records, submits and waits, and reports the GPU
// time of the dispatch from timestamp queries.
#pragma once
#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class ComputePipeline {
 public:
  // `shader`: an embedded shader's name (shader_library.h); sst::Error when it is missing.
  // `specialization`: the values of the shader's specialization constants, by the ids of
  // gpu/shaders/specialization_ids.h (SST_SPEC_UNSET leaves one to its run-time value).
  // `top_level`: the scene's acceleration structure; the pipeline is then the shader's ray-query
  // build (<shader>_rq, gpu/shaders/ray_queries.glsl) with the structure at binding
  // kTopLevelBinding, and dispatch() ignores the buffer given for that binding.
  ComputePipeline(const VulkanContext& context, const std::string& shader, uint32_t buffer_count,
                  uint32_t push_constant_bytes, std::vector<uint32_t> specialization = {},
                  VkAccelerationStructureKHR top_level = VK_NULL_HANDLE);

  // The binding of the scene's top-level acceleration structure in the ray-query kernels: that of
  // the flat BVH's nodes in the others (GpuRenderContext::scene_buffers).
  static constexpr uint32_t kTopLevelBinding = 5;
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  // Runs groups_x * groups_y workgroups with `buffers` bound in order and `push` (of the size
  // given at creation) as push constants. Waits at most `timeout_s` (wait_for_device: a lost
  // device is an sst::Error, a hung one ends the process with one line, never a hung process).
  // Returns the GPU time in ms (timestamps).
  double dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                  uint32_t groups_y = 1, double timeout_s = 120.0);

 private:
  const VulkanContext& context_;
  std::string name_;
  uint32_t buffer_count_, push_bytes_;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkAccelerationStructureKHR top_level_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  float timestamp_period_ns_ = 1.0f;
};

}  // namespace sst::gpu
