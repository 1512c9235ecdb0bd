#include "core/pipeline/backend.h"

#include "core/render/render_options.h"
#include "core/util/error.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/shader_library.h"
#include "gpu/vulkan_context.h"
#endif

namespace sst {

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

namespace {

bool shaders_built_in() {
#ifdef SST_HAVE_VULKAN
  return !gpu::embedded_spirv("many_light").empty();
#else
  return false;
#endif
}

// The device that would run, or throws the reason it cannot (one line).
DeviceInfo usable_device(int device) {
  std::string reason;
  std::vector<DeviceInfo> devices = list_vulkan_devices(&reason);
  if (devices.empty()) throw Error("backend 'vulkan': no Vulkan device (" + reason + ")");
  if (device < 0 || device >= int(devices.size()))
    throw Error("backend 'vulkan': device " + std::to_string(device) + " does not exist (" +
                std::to_string(devices.size()) + " found; see sst-render --list-devices)");
  if (!shaders_built_in()) throw Error("backend 'vulkan': this build has no shaders (glslc was not found)");
  return devices[size_t(device)];
}

}  // namespace

std::string resolve_backend(const std::string& requested, int device, std::string* message) {
  if (message) message->clear();
  if (requested == "cpu") return "cpu";
  if (requested == "vulkan") {
    usable_device(device);
    return "vulkan";
  }
  if (requested == "auto") {
    try {
      DeviceInfo d = usable_device(device);
      if (d.type == "cpu") {
        if (message) *message = "auto: Vulkan device " + std::to_string(device) + " (" + d.name +
                                ") runs on the CPU; using the cpu backend (Embree)";
        return "cpu";
      }
      if (message) *message = "auto: using vulkan on device " + std::to_string(device) + " (" + d.name + ")";
      return "vulkan";
    } catch (const Error& e) {
      if (message) *message = std::string(e.what()) + "; auto: using the cpu backend";
      return "cpu";
    }
  }
  throw Error("unknown backend '" + requested + "' (valid: " + backend_names() + ")");
}

}  // namespace sst
