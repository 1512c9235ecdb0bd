// `gi10`: GI-1.0 (Boisse et al. 2022, AMD; specified in docs/design/gi10.md), two-level radiance
// caching: screen probes traced at 1/4 ray per pixel and a world-space hash-grid cache of
// radiance at their hits, reprojected, filtered and denoised over frames. sst adds its direct
// pass (every method's, core/pt) so that images compare with the other methods.
//
// The frame's order of stages, its constants and its compose live here once (Gi10Renderer); the
// stages' element work is gi10_stages.h; where the elements run is a Gi10Executor: oneTBB loops
// on the CPU (this folder), dispatches of gpu/shaders/gi10.comp on Vulkan (gpu/gi10_vulkan.h).
#pragma once
#include <memory>
#include <span>
#include <vector>

#include "core/gi10/gi10_layout.h"
#include "core/gi10/gi10_params.h"
#include "core/render/method.h"

namespace sst {

// The element counts of one resolution and cache size.
struct Gi10Sizes {
  uint32_t width = 0, height = 0;
  uint32_t tiles_x = 0, tiles_y = 0, spawn_x = 0, spawn_y = 0;
  uint32_t mask_levels = 0, mask_total = 0;  // mips of the probe mask and their elements (one copy)
  uint32_t hash_tiles = 0;
  uint32_t reservoir_slots = 0;  // world-space ReSTIR's reservoir slots (0: world_restir off)
  uint32_t side_slots = 0;       // side_cache's slots, one per screen tile (0: side_cache off)
  uint64_t pixels() const { return uint64_t(width) * height; }
  uint64_t tiles() const { return uint64_t(tiles_x) * tiles_y; }
  uint64_t spawns() const { return uint64_t(spawn_x) * spawn_y; }
  // Blocks of the spawn stage's list compaction (override flags, then empty-tile flags).
  uint64_t list_blocks() const;
  uint64_t spawn_words() const;  // the SPAWN buffer's elements (gi10_buffers.h), side_cache's included
  uint64_t radiance_entries() const;  // the RADIANCE buffer's: two probe grids, side_cache's slots
  uint64_t hash_words() const;   // the HASH buffer's: checksums, touches, world_restir's keys
  // world_restir's buffers (gi10_buffers.h), one element each when it is off: RAY_RESERVOIRS and
  // each of SLOT_RESERVOIRS and SLOT_SURFACES.
  uint64_t ray_reservoirs() const;
  uint64_t slot_entries() const;
  bool operator==(const Gi10Sizes&) const = default;
};
Gi10Sizes gi10_sizes(int width, int height, const Gi10Params& params);
// The tile grid of mip `level` of the probe mask (as gi_mask_size of gi10_stages.h computes it).
glm::uvec2 gi10_mask_level_size(const Gi10Sizes& sizes, uint32_t level);

// Where the stages run. Every buffer starts zeroed (the probe mask: no probe) after allocate().
class Gi10Executor {
 public:
  virtual ~Gi10Executor() = default;
  virtual void allocate(const Gi10Sizes& sizes) = 0;
  // Before the frame's first stage: its inputs and constants.
  virtual void begin_frame(const RenderContext& context, const glsl::Gi10Frame& frame) = 0;
  // Runs `stage` (GI10_STAGE_*) over elements [0, count); returns its time in ms (the device's
  // own timestamps on a GPU).
  virtual double run(uint32_t stage, uint32_t pass, uint32_t count) = 0;
  virtual void clear_counters() = 0;
  virtual std::vector<uint32_t> counters() = 0;
  // E_out (OUTPUT) and the interpolated irradiance before the denoiser (DENOISE's first image).
  virtual void read_irradiance(std::vector<glm::vec4>& denoised, std::vector<glm::vec4>& raw) = 0;
  virtual void read_pixels(std::vector<glsl::Gi10Pixel>& pixels) = 0;  // this frame's G-buffer
  virtual void write_feedback(const std::vector<glm::vec4>& image) = 0;
  // The direct pass and first-hit AOVs of every method (pt with max_bounces 0) for this frame.
  virtual FrameOutput direct(const RenderContext& context, StageTimer& timer) = 0;
  // Every buffer but the frame constants', in gi10_buffers.h's order, as its bytes in place: what
  // Gi10Renderer::save reads and restore writes after allocate().
  virtual std::vector<std::span<const uint8_t>> buffers() const = 0;
  virtual std::vector<std::span<uint8_t>> buffers() = 0;
};

// The frames of one GI-1.0 run: its persistent state is the executor's buffers plus what is kept
// here (previous camera, frame counter, the scene-relative cell base).
class Gi10Renderer {
 public:
  explicit Gi10Renderer(const Gi10Params& params);
  // Frame `context.frame` of a sequence; frame 0 (or a new size) starts over with warm-up frames.
  FrameOutput render(const RenderContext& context, Gi10Executor& executor, StageTimer& timer);
  const Gi10Params& params() const { return params_; }
  // The run's state, this object's and the executor's buffers, as bytes (empty before the first
  // frame): Gi10Method::save_history's, and on Vulkan what carries the caches to the next device
  // context. restore() allocates `executor` and fills its buffers, and the next frame goes on as if
  // never interrupted. Throws sst::Error when the bytes are not such a state of this build.
  std::vector<uint8_t> save(const Gi10Executor& executor) const;
  void restore(std::span<const uint8_t> bytes, Gi10Executor& executor);

 private:
  FrameOutput render_one(const RenderContext& context, Gi10Executor& executor, StageTimer& timer, bool warmup);

  Gi10Params params_;
  Gi10Resolved resolved_;
  Gi10Sizes sizes_;
  bool started_ = false;
  uint32_t frame_ = 0;  // frames rendered since the start, warm-up included
  glsl::ViewParams previous_view_{};
  float view_length_ = 0.0f;
};

class Gi10Method final : public Method {
 public:
  explicit Gi10Method(const Gi10Params& params);
  ~Gi10Method() override;
  FrameOutput render(const RenderContext& context, StageTimer& timer) override;
  nlohmann::json params() const override;
  // Its whole state (Gi10Renderer::save), for sequence checkpoints: the caches are in world space
  // and outlive pose changes.
  std::vector<uint8_t> save_history() const override { return renderer_.save(*cpu_); }
  void restore_history(std::span<const uint8_t> bytes, bool) override { renderer_.restore(bytes, *cpu_); }
  Gi10Renderer& renderer() { return renderer_; }

 private:
  Gi10Renderer renderer_;
  std::unique_ptr<Gi10Executor> cpu_;
};

MethodInfo gi10_method_info();

}  // namespace sst
