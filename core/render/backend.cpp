#include "core/render/backend.h"

#include "core/util/error.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/vulkan_context.h"
#endif

namespace sst {

std::string api_version_string(uint32_t v) {
  // VK_API_VERSION_MAJOR/MINOR/PATCH, spelled out so this compiles without Vulkan headers.
  return std::to_string((v >> 22) & 0x7Fu) + "." + std::to_string((v >> 12) & 0x3FFu) + "." +
         std::to_string(v & 0xFFFu);
}

std::vector<DeviceInfo> list_vulkan_devices(std::string* reason) {
  if (reason) reason->clear();
#ifdef SST_HAVE_VULKAN
  try {
    std::vector<DeviceInfo> devices = gpu::enumerate_devices();
    if (devices.empty() && reason) *reason = "no Vulkan device with a compute queue";
    return devices;
  } catch (const std::exception& e) {
    if (reason) *reason = e.what();
    return {};
  }
#else
  if (reason) *reason = "built without Vulkan";
  return {};
#endif
}

const char* backend_names() { return "cpu, vulkan, auto"; }

std::string resolve_backend(const std::string& requested, int device, std::string* message) {
  if (message) message->clear();
  if (requested == "cpu") return "cpu";
  if (requested == "auto") {
    if (message) *message = "vulkan backend has no methods yet (issue 5); using cpu";
    return "cpu";
  }
  if (requested == "vulkan") {
    std::string reason;
    std::vector<DeviceInfo> devices = list_vulkan_devices(&reason);
    if (devices.empty()) throw Error("backend 'vulkan': no Vulkan device (" + reason + ")");
    if (device < 0 || device >= int(devices.size()))
      throw Error("backend 'vulkan': device " + std::to_string(device) + " does not exist (" +
                  std::to_string(devices.size()) + " found; see sst-render --list-devices)");
    throw Error("backend 'vulkan': not implemented yet (issue 5); use --backend cpu");
  }
  throw Error("unknown backend '" + requested + "' (valid: " + backend_names() + ")");
}

}  // namespace sst
