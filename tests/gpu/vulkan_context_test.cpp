// The Vulkan groundwork: device enumeration, context creation, device selection errors,
// and backend resolution. Device tests skip, with the reason, where no Vulkan device exists.
#include <gtest/gtest.h>

#include <string>

#include "core/pipeline/backend.h"
#include "core/util/error.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/vulkan_context.h"
#include "gpu/shader_library.h"
#endif

namespace sst {
namespace {

// The sst::Error message of f(), or "" when it does not throw one.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(VulkanContext, ListsDevicesOrGivesReason) {
  std::string reason;
  std::vector<DeviceInfo> devices = list_vulkan_devices(&reason);
  if (devices.empty()) {
    EXPECT_FALSE(reason.empty());
    GTEST_SKIP() << "no Vulkan device: " << reason;
  }
  EXPECT_TRUE(reason.empty()) << reason;
  for (size_t i = 0; i < devices.size(); ++i) {
    const DeviceInfo& d = devices[i];
    EXPECT_EQ(d.index, int(i));
    EXPECT_FALSE(d.name.empty());
    EXPECT_TRUE(d.type == "cpu" || d.type == "integrated" || d.type == "discrete" || d.type == "virtual" ||
                d.type == "other")
        << d.type;
    EXPECT_GE(d.api_version, (1u << 22) | (2u << 12)) << api_version_string(d.api_version);  // >= 1.2
    EXPECT_GE(d.max_storage_buffer_range, uint64_t(1) << 27);  // Vulkan's required minimum
    EXPECT_GE(d.max_compute_workgroup_invocations, 128u);      // ditto
  }
}

TEST(VulkanContext, ApiVersionString) {
  EXPECT_EQ(api_version_string((1u << 22) | (3u << 12) | 230u), "1.3.230");
}

#ifdef SST_HAVE_VULKAN
TEST(VulkanContext, CreatesAndDestroysContextOnDevice0) {
  std::string reason;
  if (list_vulkan_devices(&reason).empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  for (int round = 0; round < 2; ++round) {  // twice: destruction leaves nothing behind
    gpu::VulkanContext context(0);
    EXPECT_NE(context.instance(), VK_NULL_HANDLE);
    EXPECT_NE(context.physical_device(), VK_NULL_HANDLE);
    EXPECT_NE(context.device(), VK_NULL_HANDLE);
    EXPECT_NE(context.compute_queue(), VK_NULL_HANDLE);
    EXPECT_EQ(context.info().index, 0);
    EXPECT_FALSE(context.info().name.empty());
    EXPECT_EQ(vkQueueWaitIdle(context.compute_queue()), VK_SUCCESS);
  }
}

TEST(VulkanContext, BadIndexIsOneClearLine) {
  std::string reason;
  std::vector<DeviceInfo> devices = list_vulkan_devices(&reason);
  if (devices.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  for (int bad : {int(devices.size()), -1}) {
    std::string message = error_of([&] { gpu::VulkanContext context(bad); });
    EXPECT_NE(message.find("Vulkan device " + std::to_string(bad) + " does not exist"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}
#endif

TEST(Backend, CpuResolvesToCpuWithoutNote) {
  std::string message = "stale";
  EXPECT_EQ(resolve_backend("cpu", 0, &message), "cpu");
  EXPECT_EQ(message, "");
  EXPECT_EQ(resolve_backend("cpu", 0, nullptr), "cpu");
}

// auto runs on a GPU when there is one; lavapipe (a CPU device) or no device at all means the CPU
// backend, with a note saying why.
TEST(Backend, AutoPicksAGpuAndOtherwiseTheCpuWithANote) {
  std::string message, reason;
  std::string chosen = resolve_backend("auto", 0, &message);
  std::vector<DeviceInfo> devices = list_vulkan_devices(&reason);
  bool gpu = !devices.empty() && devices[0].type != "cpu";
#ifdef SST_HAVE_VULKAN
  gpu = gpu && !gpu::embedded_spirv("many_light").empty();
#endif
  EXPECT_EQ(chosen, gpu ? "vulkan" : "cpu");
  EXPECT_NE(message.find("auto: "), std::string::npos) << message;
  if (!devices.empty()) {
    EXPECT_NE(message.find(devices[0].name), std::string::npos) << message;
  }
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(Backend, VulkanResolvesWhenADeviceExistsElseNamesWhyNot) {
  std::string reason;
  bool has_device = !list_vulkan_devices(&reason).empty();
  if (has_device) {
    EXPECT_EQ(resolve_backend("vulkan", 0, nullptr), "vulkan");
  } else {
    std::string message = error_of([] { resolve_backend("vulkan", 0, nullptr); });
    EXPECT_EQ(message, "backend 'vulkan': no Vulkan device (" + reason + ")");
  }
}

TEST(Backend, VulkanWithMissingDeviceNamesIt) {
  std::string reason;
  if (list_vulkan_devices(&reason).empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  std::string message = error_of([] { resolve_backend("vulkan", 1000, nullptr); });
  EXPECT_NE(message.find("backend 'vulkan': device 1000 does not exist"), std::string::npos) << message;
}

TEST(Backend, UnknownBackendNamesValidValues) {
  std::string message = error_of([] { resolve_backend("metal", 0, nullptr); });
  EXPECT_EQ(message, "unknown backend 'metal' (valid: cpu, vulkan, auto)");
}

}  // namespace
}  // namespace sst
