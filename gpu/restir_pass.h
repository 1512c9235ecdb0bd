// ReSTIR on the GPU (gpu/shaders/restir.comp): the twin of run_restir (core/restir/restir.h), the
// same passes in the same order per pixel, so that with --accel flat the backends add the same
// bits to a frame. ReSTIR DI as every method's direct light here; ReSTIR GI's method in
// gpu/restir_gi_vulkan.h.
#pragma once
#include <array>
#include <memory>

#include "core/render/frame_layout.h"
#include "core/render/method.h"
#include "core/restir/restir.h"
#include "core/util/stage_timer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"

namespace sst::gpu {

class GpuRenderContext;

// The six stages' pipelines (restir_0 .. _5), compiled for gpu's light sampler and acceleration
// structure.
struct RestirPipelines {
  std::array<std::unique_ptr<ComputePipeline>, 6> stages;
};
std::unique_ptr<RestirPipelines> make_restir_pipelines(const GpuRenderContext& gpu);

// RestirHistory (core/restir/restir.h) on the device; between two devices (a pose change makes the
// scene's device context again) on the host, in `parked`.
struct GpuRestirHistory {
  std::unique_ptr<GpuBuffer> surfaces, reservoirs, view;
  glsl::ViewParams view_params{};
  RestirSampleSpace space;
  bool valid = false;
  bool posed = false;
  RestirHistory parked;
};

// The history on the host: read back from the device, or the parked one.
RestirHistory download_restir_history(const GpuRestirHistory& history);

// Moves the history to the host and releases its buffers, before their device goes: the scene is
// posed anew, so the next run_restir uploads it as a posed history.
void park_restir_history(GpuRestirHistory& history);

// A history from the host (a sequence checkpoint's) that the next run_restir uploads, `posed` or
// not.
void restore_restir_history(GpuRestirHistory& history, RestirHistory host, bool posed);

// run_restir on the GPU. Records the dispatches' times in frame.method_counters["gpu_ms"][stage].
void run_restir(const RenderContext& ctx, const GpuRenderContext& gpu, RestirPipelines& pipelines, RestirKind kind,
                const RestirPush& base, const RestirReuse& reuse, GpuRestirHistory& history, const char* stage,
                StageTimer& timer, FrameOutput& frame);

// add_restir_direct (core/restir/restir_di.h) on the GPU.
void add_restir_direct(const RenderContext& ctx, const GpuRenderContext& gpu, RestirPipelines& pipelines,
                       StageTimer& timer, FrameOutput& frame, GpuRestirHistory& history);

}  // namespace sst::gpu
