// Which backend a render runs on. Backend-neutral: compiled in every build; the Vulkan parts
// answer "built without Vulkan" when the build has no Vulkan (SST_HAVE_VULKAN undefined).
#pragma once
#include <string>
#include <vector>

#include "core/util/device_info.h"

namespace sst {

// The Vulkan devices with a compute queue; never throws. Empty when there is none, with the reason
// (no driver, no device, built without Vulkan) in *reason when given.
std::vector<DeviceInfo> list_vulkan_devices(std::string* reason = nullptr);

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
