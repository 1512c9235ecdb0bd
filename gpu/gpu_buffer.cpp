#include "gpu/gpu_buffer.h"

#include <string>

#include "core/util/error.h"

namespace sst::gpu {
namespace {

std::string mib(size_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The first memory type allowed by `bits` with all `wanted` properties; UINT32_MAX if none.
uint32_t find_memory_type(VkPhysicalDevice physical, uint32_t bits, VkMemoryPropertyFlags wanted) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  return UINT32_MAX;
}

}  // namespace

GpuBuffer::GpuBuffer(const VulkanContext& context, size_t bytes, VkBufferUsageFlags usage)
    : device_(context.device()), bytes_(bytes) {
  if (bytes == 0) bytes_ = bytes = 16;  // Vulkan forbids empty buffers; an empty array still binds
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && bytes > context.info().max_storage_buffer_range)
    throw Error("GPU buffer of " + mib(bytes) + " exceeds the device's storage-buffer limit of " +
                mib(context.info().max_storage_buffer_range) + " (" + context.info().name + ")");
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = bytes;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (vkCreateBuffer(device_, &info, nullptr, &buffer_) != VK_SUCCESS) throw Error("vkCreateBuffer failed (" + mib(bytes) + ")");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, buffer_, &req);
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  uint32_t type = find_memory_type(context.physical_device(), req.memoryTypeBits, host | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type == UINT32_MAX) type = find_memory_type(context.physical_device(), req.memoryTypeBits, host);
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  VkMemoryAllocateFlagsInfo flags = vk_struct<VkMemoryAllocateFlagsInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO);
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) alloc.pNext = &flags;
  if (type == UINT32_MAX || vkAllocateMemory(device_, &alloc, nullptr, &memory_) != VK_SUCCESS) {
    vkDestroyBuffer(device_, buffer_, nullptr);
    throw Error("out of GPU memory allocating " + mib(bytes) + " on " + context.info().name);
  }
  vkBindBufferMemory(device_, buffer_, memory_, 0);
  if (vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_) != VK_SUCCESS) {
    vkFreeMemory(device_, memory_, nullptr);
    vkDestroyBuffer(device_, buffer_, nullptr);
    throw Error("cannot map a GPU buffer of " + mib(bytes));
  }
}

VkDeviceAddress GpuBuffer::device_address() const {
  VkBufferDeviceAddressInfo info = vk_struct<VkBufferDeviceAddressInfo>(VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO);
  info.buffer = buffer_;
  return vkGetBufferDeviceAddress(device_, &info);
}

GpuBuffer::~GpuBuffer() {
  if (mapped_) vkUnmapMemory(device_, memory_);
  if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
  if (memory_) vkFreeMemory(device_, memory_, nullptr);
}

void GpuBuffer::check_fits(size_t bytes) const {
  if (bytes > bytes_) throw Error("GPU buffer transfer of " + std::to_string(bytes) + " bytes into " + std::to_string(bytes_));
}

}  // namespace sst::gpu
