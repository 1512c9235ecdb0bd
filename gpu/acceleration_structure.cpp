#include "gpu/acceleration_structure.h"

#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace sst::gpu {
namespace {

void check(VkResult r, const std::string& what) {
  if (r != VK_SUCCESS)
    throw Error("acceleration structure: " + what + " failed (VkResult " + std::to_string(int(r)) + ")");
}

// The extension's entry points, which the loader does not export.
struct AccelFunctions {
  PFN_vkGetAccelerationStructureBuildSizesKHR sizes = nullptr;
  PFN_vkCreateAccelerationStructureKHR create = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR build = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR address = nullptr;
  explicit AccelFunctions(VkDevice d) {
    sizes = reinterpret_cast<PFN_vkGetAccelerationStructureBuildSizesKHR>(
        vkGetDeviceProcAddr(d, "vkGetAccelerationStructureBuildSizesKHR"));
    create = reinterpret_cast<PFN_vkCreateAccelerationStructureKHR>(
        vkGetDeviceProcAddr(d, "vkCreateAccelerationStructureKHR"));
    destroy = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(
        vkGetDeviceProcAddr(d, "vkDestroyAccelerationStructureKHR"));
    build = reinterpret_cast<PFN_vkCmdBuildAccelerationStructuresKHR>(
        vkGetDeviceProcAddr(d, "vkCmdBuildAccelerationStructuresKHR"));
    address = reinterpret_cast<PFN_vkGetAccelerationStructureDeviceAddressKHR>(
        vkGetDeviceProcAddr(d, "vkGetAccelerationStructureDeviceAddressKHR"));
    if (!sizes || !create || !destroy || !build || !address)
      throw Error("acceleration structure: the driver lacks VK_KHR_acceleration_structure's functions");
  }
};

constexpr VkBufferUsageFlags kInputUsage =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr VkBufferUsageFlags kStorageUsage =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr VkBufferUsageFlags kScratchUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// One build: its geometry description, sizes and the structure made for it.
struct Level {
  VkAccelerationStructureGeometryKHR geometry =
      vk_struct<VkAccelerationStructureGeometryKHR>(VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR);
  VkAccelerationStructureBuildGeometryInfoKHR info = vk_struct<VkAccelerationStructureBuildGeometryInfoKHR>(
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR);
  VkAccelerationStructureBuildSizesInfoKHR sizes = vk_struct<VkAccelerationStructureBuildSizesInfoKHR>(
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR);
  VkAccelerationStructureBuildRangeInfoKHR range{};

  void prepare(const AccelFunctions& f, VkDevice device, VkAccelerationStructureTypeKHR type, uint32_t count) {
    info.type = type;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = 1;
    info.pGeometries = &geometry;
    range.primitiveCount = count;
    f.sizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &count, &sizes);
  }

  // The structure in a buffer of its own; `out` receives both.
  void create(const AccelFunctions& f, const VulkanContext& context, std::unique_ptr<GpuBuffer>& buffer,
              VkAccelerationStructureKHR& out) {
    buffer = std::make_unique<GpuBuffer>(context, size_t(sizes.accelerationStructureSize), kStorageUsage);
    VkAccelerationStructureCreateInfoKHR ci =
        vk_struct<VkAccelerationStructureCreateInfoKHR>(VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR);
    ci.buffer = buffer->handle();
    ci.size = sizes.accelerationStructureSize;
    ci.type = info.type;
    check(f.create(context.device(), &ci, nullptr, &out), "vkCreateAccelerationStructureKHR");
    info.dstAccelerationStructure = out;
  }
};

VkDeviceAddress aligned(VkDeviceAddress a, VkDeviceAddress alignment) {
  return alignment > 1 ? (a + alignment - 1) / alignment * alignment : a;
}

}  // namespace

GpuAccelerationStructure::GpuAccelerationStructure(const VulkanContext& context, const Scene& scene)
    : context_(context) {
  if (!context.info().ray_query)
    throw Error("--accel rayquery: " + context.info().name + " has no ray queries (VK_KHR_ray_query)");
  const auto start = std::chrono::steady_clock::now();
  VkDevice dev = context.device();
  AccelFunctions f(dev);
  triangles_ = uint32_t(scene.triangles.size());
  for (size_t t = 0; t < scene.triangles.size() && opaque_; ++t) {
    uint32_t m = t < scene.triangle_material.size() ? scene.triangle_material[t] : 0u;
    if (m < scene.materials.size() && scene.materials[m].alpha_mode != AlphaMode::Opaque) opaque_ = false;
  }

  // Inputs: tight positions and indices (the scene's vertex and triangle arrays on the GPU carry
  // other fields between them).
  positions_ = std::make_unique<GpuBuffer>(context, scene.positions.size() * sizeof(float) * 3, kInputUsage);
  std::vector<float> xyz(scene.positions.size() * 3);
  for (size_t i = 0; i < scene.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) xyz[3 * i + size_t(c)] = scene.positions[i][c];
  positions_->upload(std::span<const float>(xyz));
  indices_ = std::make_unique<GpuBuffer>(context, scene.triangles.size() * sizeof(uint32_t) * 3, kInputUsage);
  std::vector<uint32_t> idx(scene.triangles.size() * 3);
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) idx[3 * t + size_t(c)] = scene.triangles[t][c];
  indices_->upload(std::span<const uint32_t>(idx));

  Level bottom;
  bottom.geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  bottom.geometry.flags = opaque_ ? VK_GEOMETRY_OPAQUE_BIT_KHR : VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR;
  VkAccelerationStructureGeometryTrianglesDataKHR& tri = bottom.geometry.geometry.triangles;
  tri.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  tri.vertexData.deviceAddress = positions_->device_address();
  tri.vertexStride = sizeof(float) * 3;
  tri.maxVertex = scene.positions.empty() ? 0u : uint32_t(scene.positions.size() - 1);
  tri.indexType = VK_INDEX_TYPE_UINT32;
  tri.indexData.deviceAddress = indices_->device_address();
  bottom.prepare(f, dev, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, triangles_);
  bottom.create(f, context, bottom_buffer_, bottom_);

  VkAccelerationStructureDeviceAddressInfoKHR address_info = vk_struct<VkAccelerationStructureDeviceAddressInfoKHR>(
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR);
  address_info.accelerationStructure = bottom_;
  VkAccelerationStructureInstanceKHR instance{};
  instance.transform.matrix[0][0] = instance.transform.matrix[1][1] = instance.transform.matrix[2][2] = 1.0f;
  instance.mask = 0xFF;
  instance.accelerationStructureReference = f.address(dev, &address_info);
  instances_ = std::make_unique<GpuBuffer>(context, sizeof(instance), kInputUsage);
  std::memcpy(instances_->data(), &instance, sizeof(instance));

  Level top;
  top.geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  top.geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  top.geometry.geometry.instances.data.deviceAddress = instances_->device_address();
  top.prepare(f, dev, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, 1u);
  top.create(f, context, top_buffer_, top_);

  // One scratch buffer serves both builds, the barrier between them ordering its reuse.
  VkPhysicalDeviceAccelerationStructurePropertiesKHR props =
      vk_struct<VkPhysicalDeviceAccelerationStructurePropertiesKHR>(
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR);
  VkPhysicalDeviceProperties2 p2 =
      vk_struct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
  p2.pNext = &props;
  vkGetPhysicalDeviceProperties2(context.physical_device(), &p2);
  const VkDeviceAddress alignment = props.minAccelerationStructureScratchOffsetAlignment;
  scratch_bytes_ = size_t(std::max(bottom.sizes.buildScratchSize, top.sizes.buildScratchSize) + alignment);
  GpuBuffer scratch(context, scratch_bytes_, kScratchUsage);
  bottom.info.scratchData.deviceAddress = aligned(scratch.device_address(), alignment);
  top.info.scratchData.deviceAddress = bottom.info.scratchData.deviceAddress;

  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandPoolCreateInfo pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pool_info.queueFamilyIndex = context.compute_queue_family();
  check(vkCreateCommandPool(dev, &pool_info, nullptr, &pool), "command pool");
  VkQueryPool queries = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  try {
    VkCommandBufferAllocateInfo alloc =
        vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(dev, &alloc, &cmd), "command buffer");
    VkQueryPoolCreateInfo query_info = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    check(vkCreateQueryPool(dev, &query_info, nullptr, &queries), "query pool");
    VkCommandBufferBeginInfo begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "begin");
    vkCmdResetQueryPool(cmd, queries, 0, 2);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries, 0);
    const VkAccelerationStructureBuildRangeInfoKHR* bottom_range = &bottom.range;
    f.build(cmd, 1, &bottom.info, &bottom_range);
    VkMemoryBarrier barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    barrier.dstAccessMask =
        VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    const VkAccelerationStructureBuildRangeInfoKHR* top_range = &top.range;
    f.build(cmd, 1, &top.info, &top_range);
    barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, 1);
    check(vkEndCommandBuffer(cmd), "end");
    VkFenceCreateInfo fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    check(vkCreateFence(dev, &fence_info, nullptr, &fence), "fence");
    VkSubmitInfo submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    check(vkQueueSubmit(context.compute_queue(), 1, &submit, fence), "submit");
    wait_for_device(context, fence, 120.0, "acceleration structure build");
    uint64_t stamps[2] = {0, 0};
    check(vkGetQueryPoolResults(dev, queries, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "timestamps");
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(context.physical_device(), &p);
    build_gpu_ms_ = double(stamps[1] - stamps[0]) * double(p.limits.timestampPeriod) * 1e-6;
  } catch (...) {
    if (fence) vkDestroyFence(dev, fence, nullptr);
    if (queries) vkDestroyQueryPool(dev, queries, nullptr);
    vkDestroyCommandPool(dev, pool, nullptr);
    f.destroy(dev, top_, nullptr);
    f.destroy(dev, bottom_, nullptr);
    throw;
  }
  vkDestroyFence(dev, fence, nullptr);
  vkDestroyQueryPool(dev, queries, nullptr);
  vkDestroyCommandPool(dev, pool, nullptr);
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

GpuAccelerationStructure::~GpuAccelerationStructure() {
  VkDevice dev = context_.device();
  auto destroy = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(
      vkGetDeviceProcAddr(dev, "vkDestroyAccelerationStructureKHR"));
  if (destroy) {
    if (top_) destroy(dev, top_, nullptr);
    if (bottom_) destroy(dev, bottom_, nullptr);
  }
}

nlohmann::json GpuAccelerationStructure::describe() const {
  return {{"triangles", triangles_},
          {"opaque", opaque_},
          {"bottom_level_bytes", bottom_buffer_ ? bottom_buffer_->size() : 0},
          {"top_level_bytes", top_buffer_ ? top_buffer_->size() : 0},
          {"input_bytes", positions_->size() + indices_->size() + instances_->size()},
          {"scratch_bytes", scratch_bytes_},
          {"build_ms", build_ms_},
          {"build_gpu_ms", build_gpu_ms_}};
}

}  // namespace sst::gpu
