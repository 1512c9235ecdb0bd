// A Vulkan physical device as the record and the front ends describe it. Plain data without Vulkan
// headers, so that builds without Vulkan still compile the code that prints or records it.
#pragma once
#include <cstdint>
#include <string>

namespace sst {

// One Vulkan physical device that has a compute queue. `index` is its position among such devices
// (the number --device / VulkanContext take), in the loader's enumeration order.
struct DeviceInfo {
  int index = 0;
  std::string name;
  std::string type;    // "cpu", "integrated", "discrete", "virtual" or "other"
  std::string driver;  // driver name and info (e.g. "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)"); "" if unknown
  uint32_t api_version = 0;  // VK_MAKE_API_VERSION encoding
  uint64_t max_storage_buffer_range = 0;  // bytes
  uint32_t max_compute_workgroup_invocations = 0;
  // VK_KHR_acceleration_structure and VK_KHR_ray_query with their features: --accel rayquery
  // can run (gpu/acceleration_structure.h).
  bool ray_query = false;
};

// "1.3.230" from a Vulkan API version number.
std::string api_version_string(uint32_t api_version);

}  // namespace sst
