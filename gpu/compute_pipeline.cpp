#include "gpu/compute_pipeline.h"

#include <cstdint>

#include "core/util/error.h"
#include "gpu/shader_library.h"

namespace sst::gpu {
namespace {

void check(VkResult result, const std::string& what) {
  if (result == VK_SUCCESS) return;
  if (result == VK_ERROR_DEVICE_LOST) throw Error(what + ": the GPU device was lost");
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    throw Error(what + ": out of memory");
  throw Error(what + " failed (VkResult " + std::to_string(int(result)) + ")");
}

}  // namespace

ComputePipeline::ComputePipeline(const VulkanContext& context, const std::string& shader, uint32_t buffer_count,
                                 uint32_t push_constant_bytes, std::vector<uint32_t> specialization,
                                 VkAccelerationStructureKHR top_level)
    : context_(context),
      name_(top_level ? shader + "_rq" : shader),
      buffer_count_(buffer_count),
      push_bytes_(push_constant_bytes),
      top_level_(top_level) {
  if (top_level && buffer_count <= kTopLevelBinding)
    throw Error("shader " + name_ + ": an acceleration structure needs binding " + std::to_string(kTopLevelBinding));
  VkDevice dev = context.device();
  std::span<const uint32_t> spirv = embedded_spirv(name_);
  if (spirv.empty()) throw Error("shader '" + name_ + "' is not built in (was glslc found at configure time?)");
  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = spirv.size_bytes();
  module_info.pCode = spirv.data();
  check(vkCreateShaderModule(dev, &module_info, nullptr, &module_), "shader " + name_);

  std::vector<VkDescriptorSetLayoutBinding> bindings(buffer_count);
  for (uint32_t i = 0; i < buffer_count; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  if (top_level_) bindings[kTopLevelBinding].descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  VkDescriptorSetLayoutCreateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  set_info.bindingCount = buffer_count;
  set_info.pBindings = bindings.data();
  check(vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &set_layout_), "descriptor set layout");
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout_;
  layout_info.pushConstantRangeCount = push_constant_bytes ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  check(vkCreatePipelineLayout(dev, &layout_info, nullptr, &layout_), "pipeline layout");
  VkComputePipelineCreateInfo pipe_info{};
  pipe_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipe_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipe_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipe_info.stage.module = module_;
  pipe_info.stage.pName = "main";
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)};
  VkSpecializationInfo spec_info{uint32_t(entries.size()), entries.data(), specialization.size() * sizeof(uint32_t),
                                 specialization.data()};
  if (!specialization.empty()) pipe_info.stage.pSpecializationInfo = &spec_info;
  pipe_info.layout = layout_;
  check(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &pipe_info, nullptr, &pipeline_), "pipeline " + name_);

  VkDescriptorPoolSize pool_sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, std::max(buffer_count, 1u)},
                                        {VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1u}};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = top_level_ ? 2 : 1;
  pool_info.pPoolSizes = pool_sizes;
  check(vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool_), "descriptor pool");
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout_;
  check(vkAllocateDescriptorSets(dev, &alloc, &set_), "descriptor set");

  VkCommandPoolCreateInfo cmd_pool{};

  cmd_pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  cmd_pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  cmd_pool.queueFamilyIndex = context.compute_queue_family();
  check(vkCreateCommandPool(dev, &cmd_pool, nullptr, &command_pool_), "command pool");
  VkCommandBufferAllocateInfo cmd_alloc{};
  cmd_alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  cmd_alloc.commandPool = command_pool_;
  cmd_alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cmd_alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(dev, &cmd_alloc, &commands_), "command buffer");
  VkQueryPoolCreateInfo query_info{};
  query_info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  query_info.queryCount = 2;
  check(vkCreateQueryPool(dev, &query_info, nullptr, &queries_), "timestamp queries");
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  check(vkCreateFence(dev, &fence_info, nullptr, &fence_), "fence");
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(context.physical_device(), &props);
  timestamp_period_ns_ = props.limits.timestampPeriod;
}

ComputePipeline::~ComputePipeline() {
  VkDevice dev = context_.device();
  vkDeviceWaitIdle(dev);
  if (fence_) vkDestroyFence(dev, fence_, nullptr);
  if (queries_) vkDestroyQueryPool(dev, queries_, nullptr);
  if (command_pool_) vkDestroyCommandPool(dev, command_pool_, nullptr);
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  if (pipeline_) vkDestroyPipeline(dev, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
  if (module_) vkDestroyShaderModule(dev, module_, nullptr);
}

double ComputePipeline::dispatch(const std::vector<const GpuBuffer*>& buffers, const void* push, uint32_t groups_x,
                                 uint32_t groups_y, double timeout_s) {
  if (buffers.size() != buffer_count_)
    throw Error("shader " + name_ + ": " + std::to_string(buffers.size()) + " buffers bound, " +
                std::to_string(buffer_count_) + " expected");
  VkDevice dev = context_.device();
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  VkWriteDescriptorSetAccelerationStructureKHR top_level_write =
      vk_struct<VkWriteDescriptorSetAccelerationStructureKHR>(
          VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR);
  top_level_write.accelerationStructureCount = 1;
  top_level_write.pAccelerationStructures = &top_level_;
  for (size_t i = 0; i < buffers.size(); ++i) {
    writes[i] = {};
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set_;
    writes[i].dstBinding = uint32_t(i);
    writes[i].descriptorCount = 1;
    if (top_level_ && i == kTopLevelBinding) {
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
      writes[i].pNext = &top_level_write;
      continue;
    }
    infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(dev, uint32_t(writes.size()), writes.data(), 0, nullptr);

  VkCommandBufferBeginInfo begin{};

  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands_, &begin), "begin commands");
  vkCmdResetQueryPool(commands_, queries_, 0, 2);
  vkCmdBindPipeline(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  if (push_bytes_) vkCmdPushConstants(commands_, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
  vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
  vkCmdDispatch(commands_, groups_x, groups_y, 1);
  vkCmdWriteTimestamp(commands_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
  // The host reads the buffers after the fence: make the shader's writes visible to it.
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  check(vkEndCommandBuffer(commands_), "end commands");

  VkSubmitInfo submit{};

  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  check(vkResetFences(dev, 1, &fence_), "reset fence");
  check(vkQueueSubmit(context_.compute_queue(), 1, &submit, fence_), "submit " + name_);
  wait_for_device(context_, fence_, timeout_s, "shader " + name_);
  uint64_t stamps[2] = {0, 0};
  check(vkGetQueryPoolResults(dev, queries_, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "timestamps");
  return double(stamps[1] - stamps[0]) * timestamp_period_ns_ * 1e-6;
}

}  // namespace sst::gpu
