// The Vulkan instance, the chosen physical device and a logical device with one compute queue.
// Plain Vulkan C API; built only when the Vulkan loader is found. Backend-neutral callers use
// core/pipeline/backend.h instead.
#pragma once
#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "core/util/device_info.h"

namespace sst::gpu {

// A zeroed Vulkan structure of the given type: vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO).
template <class T>
T vk_struct(VkStructureType type) {
  T v{};
  v.sType = type;
  return v;
}

// The devices with a compute queue, in index order (a temporary instance is created and destroyed).
// Throws sst::Error with one line when no instance can be created (no driver, Vulkan < 1.2).
std::vector<DeviceInfo> enumerate_devices();

// Owns a Vulkan 1.2 instance (with VK_LAYER_KHRONOS_validation in debug builds when installed),
// the physical device `device_index` (see enumerate_devices), a logical device and its first
// compute queue. Everything is destroyed in the destructor. Throws sst::Error (one line) when there
// is no driver or no device, or the index does not exist.
class VulkanContext {
 public:
  explicit VulkanContext(int device_index = 0);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  const DeviceInfo& info() const { return info_; }
  bool validation_enabled() const { return validation_; }
  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue compute_queue() const { return compute_queue_; }
  uint32_t compute_queue_family() const { return compute_queue_family_; }

 private:
  void destroy();

  DeviceInfo info_;
  bool validation_ = false;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue compute_queue_ = VK_NULL_HANDLE;
  uint32_t compute_queue_family_ = 0;
};

// Waits for `fence` of work submitted to `context`'s queue. A device error is an sst::Error. When
// the work has not finished after `timeout_s` seconds (a hung device), the process ends at once
// with one line on stderr naming `what` and exit code 1: the work still uses the buffers it was
// given, and unwinding would free them under it (lavapipe then wrote into freed memory). On a
// device that runs on the CPU (lavapipe) the limit is 10 times longer, since the first dispatch of
// a pipeline includes its compilation there.
void wait_for_device(const VulkanContext& context, VkFence fence, double timeout_s, const std::string& what);

}  // namespace sst::gpu
