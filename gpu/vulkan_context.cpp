#include "gpu/vulkan_context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/util/error.h"

namespace sst::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string result_name(VkResult r) {
  switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    default: return "VkResult " + std::to_string(int(r));
  }
}

void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw Error(std::string("Vulkan: ") + what + " failed (" + result_name(r) + ")");
}

[[maybe_unused]] bool layer_installed(const char* name) {
  uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (uint32_t i = 0; i < count; ++i)
    if (std::strcmp(layers[i].layerName, name) == 0) return true;
  return false;
}

// Creates the instance; the caller owns it. *validation says whether the layer was enabled.
VkInstance create_instance(bool* validation) {
  uint32_t loader_version = VK_API_VERSION_1_0;
  // vkEnumerateInstanceVersion exists from loader 1.1 on; a 1.0 loader cannot give us 1.2.
  auto enumerate_version = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
      vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
  if (enumerate_version) enumerate_version(&loader_version);
  if (loader_version < VK_API_VERSION_1_2)
    throw Error("Vulkan loader is version " + api_version_string(loader_version) + "; sst needs Vulkan 1.2");

  VkApplicationInfo app{};

  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "sst";
  app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.pEngineName = "sst";
  app.engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
  app.apiVersion = VK_API_VERSION_1_2;

  std::vector<const char*> layers;
#ifndef NDEBUG
  if (layer_installed(kValidationLayer)) layers.push_back(kValidationLayer);
#endif
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();

  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&info, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw Error("no Vulkan driver installed (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER)");
  check(r, "vkCreateInstance");
  *validation = !layers.empty();
  return instance;
}

// The first queue family with compute, or -1.
int compute_family(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].queueCount > 0) return int(i);
  return -1;
}

const char* type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    default: return "other";
  }
}

bool has_extension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> all(count);
  if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, all.data()) != VK_SUCCESS) return false;
  for (const VkExtensionProperties& e : all)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// The extensions that ray queries need (acceleration structures need deferred host operations).
constexpr const char* kRayQueryExtensions[] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                               VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                               VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

// The features ray queries need, chained for vkGetPhysicalDeviceFeatures2 / vkCreateDevice.
struct RayQueryFeatures {
  VkPhysicalDeviceBufferDeviceAddressFeatures address = vk_struct<VkPhysicalDeviceBufferDeviceAddressFeatures>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES);
  VkPhysicalDeviceAccelerationStructureFeaturesKHR accel = vk_struct<VkPhysicalDeviceAccelerationStructureFeaturesKHR>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR);
  VkPhysicalDeviceRayQueryFeaturesKHR query =
      vk_struct<VkPhysicalDeviceRayQueryFeaturesKHR>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR);
  VkPhysicalDeviceFeatures2 features =
      vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  RayQueryFeatures() {
    features.pNext = &address;
    address.pNext = &accel;
    accel.pNext = &query;
  }
  RayQueryFeatures(const RayQueryFeatures&) = delete;
};

bool supports_ray_query(VkPhysicalDevice device) {
  for (const char* e : kRayQueryExtensions)
    if (!has_extension(device, e)) return false;
  RayQueryFeatures f;
  vkGetPhysicalDeviceFeatures2(device, &f.features);
  return f.address.bufferDeviceAddress && f.accel.accelerationStructure && f.query.rayQuery;
}

DeviceInfo describe(VkPhysicalDevice device, int index) {
  VkPhysicalDeviceProperties p{};
  vkGetPhysicalDeviceProperties(device, &p);
  DeviceInfo d;
  d.index = index;
  d.name = p.deviceName;
  d.type = type_name(p.deviceType);
  d.api_version = p.apiVersion;
  d.max_storage_buffer_range = p.limits.maxStorageBufferRange;
  d.max_compute_workgroup_invocations = p.limits.maxComputeWorkGroupInvocations;
  d.ray_query = supports_ray_query(device);
  if (p.apiVersion >= VK_API_VERSION_1_2) {  // VkPhysicalDeviceDriverProperties is core in 1.2
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 p2{};
    p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    p2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &p2);
    d.driver = driver.driverName;
    if (driver.driverInfo[0]) d.driver += std::string(": ") + driver.driverInfo;
  }
  return d;
}

// Physical devices with a compute queue, in the loader's order.
std::vector<VkPhysicalDevice> compute_devices(VkInstance instance) {
  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> all(count);
  check(vkEnumeratePhysicalDevices(instance, &count, all.data()), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> usable;
  for (uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(all[i], &p);
    if (p.apiVersion >= VK_API_VERSION_1_2 && compute_family(all[i]) >= 0) usable.push_back(all[i]);
  }
  return usable;
}

}  // namespace

std::vector<DeviceInfo> enumerate_devices() {
  bool validation = false;
  VkInstance instance = create_instance(&validation);
  std::vector<DeviceInfo> devices;
  try {
    std::vector<VkPhysicalDevice> usable = compute_devices(instance);
    for (size_t i = 0; i < usable.size(); ++i) devices.push_back(describe(usable[i], int(i)));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return devices;
}

VulkanContext::VulkanContext(int device_index) {
  instance_ = create_instance(&validation_);
  try {
    std::vector<VkPhysicalDevice> usable = compute_devices(instance_);
    if (usable.empty()) throw Error("no Vulkan 1.2 device with a compute queue");
    if (device_index < 0 || device_index >= int(usable.size()))
      throw Error("Vulkan device " + std::to_string(device_index) + " does not exist (" + std::to_string(usable.size()) +
                  " device(s) with a compute queue, indices 0.." + std::to_string(usable.size() - 1) +
                  "; see sst-render --list-devices)");
    physical_device_ = usable[size_t(device_index)];
    info_ = describe(physical_device_, device_index);
    compute_queue_family_ = uint32_t(compute_family(physical_device_));

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = compute_queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    // Ray queries are enabled wherever the device has them; shaders without them never notice.
    RayQueryFeatures ray_query;
    if (info_.ray_query) {
      ray_query.address.bufferDeviceAddress = VK_TRUE;
      ray_query.accel.accelerationStructure = VK_TRUE;
      ray_query.query.rayQuery = VK_TRUE;
      info.pNext = &ray_query.features;
      info.enabledExtensionCount = uint32_t(std::size(kRayQueryExtensions));
      info.ppEnabledExtensionNames = kRayQueryExtensions;
    }
    check(vkCreateDevice(physical_device_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, compute_queue_family_, 0, &compute_queue_);
  } catch (...) {
    destroy();
    throw;
  }
}

void wait_for_device(const VulkanContext& context, VkFence fence, double timeout_s, const std::string& what) {
  if (context.info().type == "cpu") timeout_s *= 10.0;
  VkResult r = vkWaitForFences(context.device(), 1, &fence, VK_TRUE, uint64_t(timeout_s * 1e9));
  if (r == VK_TIMEOUT) {
    std::fprintf(stderr, "error: %s did not finish within %.0f s on %s (device hang?); exiting\n", what.c_str(),
                 timeout_s, context.info().name.c_str());
    std::fflush(nullptr);
    std::_Exit(1);
  }
  if (r == VK_ERROR_DEVICE_LOST) throw Error(what + ": the GPU device was lost");
  check(r, what.c_str());
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  compute_queue_ = VK_NULL_HANDLE;
  physical_device_ = VK_NULL_HANDLE;
  if (instance_ != VK_NULL_HANDLE) {
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

}  // namespace sst::gpu
