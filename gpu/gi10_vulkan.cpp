#include "gpu/gi10_vulkan.h"

#include <algorithm>
#include <cstring>

#include "core/gi10/gi10_math.h"
#include "core/restir/restir_layout.h"
#include "gpu/gpu_render_context.h"
#include "gpu/path_trace_pass.h"

namespace sst::gpu {
namespace {

enum Buffer : size_t {
  kFrame, kPixels, kEmission, kMask, kRadiance, kSh, kSpawn, kRays, kHash, kValues, kAccum,
  kDenoise, kAux, kFeedback, kCounters, kOutput, kRayReservoirs, kSlotReservoirs, kSlotSurfaces,
  kBufferCount
};

}  // namespace

FrameOutput VulkanGi10::render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) {
  gpu_ = &gpu;
  if (!direct_pipeline_) {
    timer.time("shader_compile", [&] {
      direct_pipeline_ = make_path_trace_pipeline(gpu.vulkan(), gpu.lights(), gpu.top_level());
      pipelines_.resize(GI10_SHADER_BUILDS);
      for (uint32_t stage = 0; stage < GI10_STAGES; ++stage) pipelines_[stage] = make_stage_pipeline(stage);
    });
  }
  if (!parked_.empty()) {
    method_.renderer().restore(parked_, *this);
    parked_.clear();
  }
  return method_.renderer().render(context, *this, timer);
}

void VulkanGi10::release_device() {
  if (!buffers_.empty()) parked_ = method_.renderer().save(*this);
  pipelines_.clear();
  direct_pipeline_.reset();
  buffers_.clear();
  bound_.clear();
  gpu_ = nullptr;
}

void VulkanGi10::allocate(const Gi10Sizes& s) {
  const VulkanContext& vk = gpu_->vulkan();
  sizes_ = s;
  uint64_t px = s.pixels(), nt = s.tiles(), ns = s.spawns(), t = s.hash_tiles;
  const std::pair<uint64_t, size_t> shapes[kBufferCount] = {
      {1, sizeof(glsl::Gi10Frame)}, {2 * px, sizeof(glsl::Gi10Pixel)}, {px, 16},  {2 * uint64_t(s.mask_total), 4},
      {s.radiance_entries(), 16},   {2 * nt * 9, 16},                 {s.spawn_words(), 4}, {ns * 64, sizeof(glsl::Gi10Ray)},
      {s.hash_words(), 4},          {t * kGiCellsPerTile, 16},                     {t * 64 * kGiAccumWords, 4},  {3 * px, 16},
      {3 * px, 16},                 {px, 16},                         {GI10_COUNTERS, 4}, {px, 16},
      {s.ray_reservoirs(), sizeof(RestirReservoir)}, {s.slot_entries(), sizeof(RestirReservoir)},
      {s.slot_entries(), sizeof(RestirSurface)}};
  const char* names[kBufferCount] = {"gi10 frame", "gi10 pixels", "gi10 emission", "gi10 probe mask",
                                     "gi10 probe radiance", "gi10 probe SH", "gi10 spawn lists", "gi10 probe rays",
                                     "gi10 hash", "gi10 cache values", "gi10 cache accumulators", "gi10 denoiser",
                                     "gi10 denoiser aux", "gi10 feedback", "gi10 counters", "gi10 irradiance",
                                     "gi10 ray reservoirs", "gi10 reservoir slots", "gi10 reservoir points"};
  buffers_.clear();
  for (size_t b = 0; b < kBufferCount; ++b) {
    buffers_.push_back(make_buffer(vk, size_t(shapes[b].first), shapes[b].second, names[b]));
    // Every buffer starts zeroed, the probe mask "no probe" (all bits set), as on the CPU.
    std::memset(buffers_.back()->data(), b == kMask ? 0xFF : 0, buffers_.back()->size());
  }
  bound_ = gpu_->scene_buffers();
  for (const auto& b : buffers_) bound_.push_back(b.get());
}

std::vector<uint8_t> VulkanGi10::save_history() const {
  return buffers_.empty() ? parked_ : method_.renderer().save(*this);
}

void VulkanGi10::restore_history(std::span<const uint8_t> bytes, bool) {
  parked_.assign(bytes.begin(), bytes.end());  // loaded with the next frame, on its device context
}

template <class Byte, class Self>
std::vector<std::span<Byte>> VulkanGi10::byte_views(Self& self) {
  std::vector<std::span<Byte>> out;
  for (size_t b = kFrame + 1; b < kBufferCount; ++b)
    out.emplace_back(static_cast<Byte*>(self.buffers_[b]->data()), self.buffers_[b]->size());
  return out;
}

std::vector<std::span<uint8_t>> VulkanGi10::buffers() { return byte_views<uint8_t>(*this); }
std::vector<std::span<const uint8_t>> VulkanGi10::buffers() const { return byte_views<const uint8_t>(*this); }

void VulkanGi10::begin_frame(const RenderContext&, const glsl::Gi10Frame& frame) {
  parity_ = frame.frame & 1u;
  shade_build_ = glsl::gi10_shade_build(frame.flags);
  buffers_[kFrame]->upload(std::span<const glsl::Gi10Frame>(&frame, 1));
}

std::unique_ptr<ComputePipeline> VulkanGi10::make_stage_pipeline(uint32_t build) const {
  return gpu_->make_pipeline("gi10_" + std::to_string(build), uint32_t(GpuRenderContext::kSceneBufferCount + kBufferCount),
                             uint32_t(sizeof(glsl::Gi10Push)));
}

double VulkanGi10::run(uint32_t stage, uint32_t pass, uint32_t count) {
  if (count == 0) return 0.0;
  glsl::Gi10Push push{stage, pass, count, 0u};
  uint32_t groups = (count + 63) / 64;
  uint32_t gx = std::min(groups, 65535u), gy = (groups + gx - 1) / gx;
  // SHADE's path and ReSTIR builds are made when a frame first needs one, outside the stage's time.
  uint32_t build = stage == GI10_STAGE_SHADE ? shade_build_ : stage;
  std::unique_ptr<ComputePipeline>& pipeline = pipelines_.at(build);
  if (!pipeline) pipeline = make_stage_pipeline(build);
  return pipeline->dispatch(bound_, &push, gx, gy);
}

void VulkanGi10::clear_counters() { std::memset(buffers_[kCounters]->data(), 0, buffers_[kCounters]->size()); }

std::vector<uint32_t> VulkanGi10::counters() {
  std::vector<uint32_t> c(GI10_COUNTERS);
  buffers_[kCounters]->download(std::span<uint32_t>(c));
  return c;
}

void VulkanGi10::read_irradiance(std::vector<glm::vec4>& denoised, std::vector<glm::vec4>& raw) {
  denoised.resize(sizes_.pixels());
  raw.resize(sizes_.pixels());
  buffers_[kOutput]->download(std::span<glm::vec4>(denoised));
  buffers_[kDenoise]->download(std::span<glm::vec4>(raw));  // its first image: the interpolated irradiance
}

void VulkanGi10::read_pixels(std::vector<glsl::Gi10Pixel>& pixels) {
  std::vector<glsl::Gi10Pixel> both(2 * sizes_.pixels());
  buffers_[kPixels]->download(std::span<glsl::Gi10Pixel>(both));
  pixels.assign(both.begin() + ptrdiff_t(parity_ * sizes_.pixels()),
                both.begin() + ptrdiff_t((parity_ + 1) * sizes_.pixels()));
}

void VulkanGi10::write_feedback(const std::vector<glm::vec4>& image) {
  buffers_[kFeedback]->upload(std::span<const glm::vec4>(image));
}

FrameOutput VulkanGi10::direct(const RenderContext& context, StageTimer& timer) {
  PathTracerParams p;
  p.max_bounces = 0;
  return timer.time("render", [&] { return render_path_tracer(*gpu_, *direct_pipeline_, context.camera, context.width, context.height,
                            context.options.seed, context.options.spp, p, render_flags(context.options))
      .frame; });
}

}  // namespace sst::gpu
