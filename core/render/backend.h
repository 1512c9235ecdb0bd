// Which backend a render runs on. Backend-neutral: compiled in every build; the Vulkan parts
// answer "built without Vulkan" when the build has no Vulkan (SST_HAVE_VULKAN undefined).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

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
};

// "1.3.230" from a Vulkan API version number.
std::string api_version_string(uint32_t api_version);

// The Vulkan devices with a compute queue; never throws. Empty when there is none, with the reason
// (no driver, no device, built without Vulkan) in *reason when given.
std::vector<DeviceInfo> list_vulkan_devices(std::string* reason = nullptr);

// The valid values of RenderOptions::backend, for error messages: "cpu, vulkan, auto".
const char* backend_names();

// Resolves a requested backend to the one that runs:
//   "cpu"    -> "cpu";
//   "vulkan" -> "vulkan" when device `device` exists and the shaders are built in; otherwise throws
//               sst::Error: "no Vulkan device (<reason>)", "device N does not exist", "built without
//               shaders";
//   "auto"   -> "vulkan" on device `device` when it exists and is a GPU, else "cpu", with a note in
//               *message either way. A CPU implementation of Vulkan (lavapipe) counts as no GPU: on
//               the same cores, Embree is faster, so auto does not pick it;
//   anything else -> throws sst::Error naming the valid values.
// *message (when given) is set to a one-line note for the user, or cleared when there is none.
std::string resolve_backend(const std::string& requested, int device, std::string* message);

}  // namespace sst
