// A storage buffer the host can map: HOST_VISIBLE | HOST_COHERENT memory, DEVICE_LOCAL too when the
// device offers such a type (integrated GPUs, lavapipe, resizable BAR), else plain host memory.
// Enough for the first backend; staging uploads to device-only memory are the step after.
#pragma once
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class GpuBuffer {
 public:
  // sst::Error naming the size when it exceeds the device's storage-buffer range (lavapipe:
  // 128 MiB) or memory runs out; never a silent overrun. `usage`: a storage buffer unless asked
  // otherwise (acceleration structures and their inputs, gpu/acceleration_structure.h).
  GpuBuffer(const VulkanContext& context, size_t bytes, VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ~GpuBuffer();
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  // For buffers made with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT.
  VkDeviceAddress device_address() const;
  size_t size() const { return bytes_; }
  void* data() { return mapped_; }
  template <class T>
  void upload(std::span<const T> values) {
    check_fits(values.size_bytes());
    std::memcpy(mapped_, values.data(), values.size_bytes());
  }
  template <class T>
  void download(std::span<T> values) const {
    check_fits(values.size_bytes());
    std::memcpy(values.data(), mapped_, values.size_bytes());
  }

 private:
  void check_fits(size_t bytes) const;
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  size_t bytes_ = 0;
};

// A new buffer of `count` elements of `element_bytes`; an allocation that fails or exceeds the
// device's limit is an sst::Error that starts with `what` and the count.
inline std::unique_ptr<GpuBuffer> make_buffer(const VulkanContext& context, size_t count, size_t element_bytes,
                                              const std::string& what) {
  try {
    return std::make_unique<GpuBuffer>(context, count * element_bytes);
  } catch (const std::exception& e) {
    throw Error(what + " (" + std::to_string(count) + "): " + e.what());
  }
}

// A new buffer holding `values` (an empty array gets GpuBuffer's 16-byte minimum).
template <class T>
std::unique_ptr<GpuBuffer> upload_buffer(const VulkanContext& context, std::span<const T> values,
                                         const std::string& what) {
  std::unique_ptr<GpuBuffer> buffer = make_buffer(context, values.size(), sizeof(T), what);
  if (!values.empty()) buffer->upload(values);
  return buffer;
}
template <class T>
std::unique_ptr<GpuBuffer> upload_buffer(const VulkanContext& context, const std::vector<T>& values,
                                         const std::string& what) {
  return upload_buffer(context, std::span<const T>(values), what);
}

}  // namespace sst::gpu
