// The compute-shader plumbing on whatever Vulkan device is present (lavapipe in CI): buffers,
// an embedded shader, dispatch, timestamps, the limits. Skips where there is no device; compiled
// only when the Vulkan backend is (SST_HAVE_VULKAN).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <bit>
#include <vector>

#include "core/pipeline/backend.h"
#include "core/rng/hash_rng.h"
#include "core/rng/sobol_sampler.h"
#include "core/util/error.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/shader_library.h"
#include "gpu/vulkan_context.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst::gpu {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

TEST(ComputePipeline, GlslRngsDrawTheSameBitsAsTheCpp) {
  SKIP_WITHOUT_GPU("rng_test");
  VulkanContext context(0);
  const uint32_t count = 4096, seed = 12345;
  GpuBuffer out(context, count * 8 * sizeof(uint32_t));
  ComputePipeline pipeline(context, "rng_test", 1, 8);
  uint32_t push[2] = {seed, count};
  double ms = pipeline.dispatch({&out}, push, (count + 63) / 64);
  EXPECT_GE(ms, 0.0);
  std::vector<uint32_t> gpu(count * 8);
  out.download(std::span<uint32_t>(gpu));
  for (uint32_t i = 0; i < count; ++i) {
    HashRng rng = hash_rng(seed, i, 7, 3);
    PixelSampler ps = pixel_sampler(seed, i, i * 3);
    vec2 a = pixel_sampler_get2d(ps), b = pixel_sampler_get2d(ps);
    uint32_t expected[8] = {pcg_hash(i), hash_rng_next_bits(rng), bits(hash_rng_next(rng)), bits(a.x),
                            bits(a.y),   bits(b.x),       bits(b.y),        sobol_dimension1(i)};
    for (int k = 0; k < 8; ++k) ASSERT_EQ(gpu[i * 8 + k], expected[k]) << "index " << i << " value " << k;
  }
}

// A dispatch that outlives its timeout ends the process with one line: throwing would unwind and
// free the buffers the device still writes (Mesa 25's lavapipe, compiling many_light.comp for 6
// minutes inside a 120 s wait, then wrote through freed memory and crashed sst-render).
TEST(ComputePipelineDeathTest, ATimedOutDispatchExitsWithOneLine) {
  SKIP_WITHOUT_GPU("rng_test");
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  auto dispatch_with_no_time = [] {
    VulkanContext context(0);
    const uint32_t count = 1u << 20;
    GpuBuffer out(context, size_t(count) * 8 * sizeof(uint32_t));
    ComputePipeline pipeline(context, "rng_test", 1, 8);
    uint32_t push[2] = {1u, count};
    pipeline.dispatch({&out}, push, count / 64, 1, 1e-9);
  };
  EXPECT_EXIT(dispatch_with_no_time(), ::testing::ExitedWithCode(1),
              "error: shader rng_test did not finish within 0 s on .*device hang");
}

TEST(ComputePipeline, BuffersBeyondTheDeviceLimitAreRefusedWithAMessage) {
  SKIP_WITHOUT_GPU("rng_test");
  VulkanContext context(0);
  size_t limit = context.info().max_storage_buffer_range;
  try {
    GpuBuffer too_big(context, limit + 1);
    FAIL() << "no error for " << limit + 1 << " bytes";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the device's storage-buffer limit"), std::string::npos) << e.what();
  }
  GpuBuffer small(context, 64);
  std::vector<uint32_t> many(100);
  EXPECT_THROW(small.upload(std::span<const uint32_t>(many)), Error);
}

TEST(ComputePipeline, WrongBindingsAndMissingShadersAreErrors) {
  SKIP_WITHOUT_GPU("rng_test");
  VulkanContext context(0);
  EXPECT_THROW(ComputePipeline(context, "no_such_shader", 1, 0), Error);
  ComputePipeline pipeline(context, "rng_test", 1, 8);
  uint32_t push[2] = {0, 0};
  EXPECT_THROW(pipeline.dispatch({}, push, 1), Error);
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
