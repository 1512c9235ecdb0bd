#include "core/util/device_info.h"

namespace sst {

std::string api_version_string(uint32_t v) {
  // VK_API_VERSION_MAJOR/MINOR/PATCH, spelled out so this compiles without Vulkan headers.
  return std::to_string((v >> 22) & 0x7Fu) + "." + std::to_string((v >> 12) & 0x3FFu) + "." +
         std::to_string(v & 0xFFFu);
}

}  // namespace sst
