// ReSTIR DI on the GPU (gpu/shaders/restir_di.comp): the twin of add_restir_direct
// (core/restir/restir_di.h), the same stages in the same order per pixel, so that with
// --accel flat the two add the same bits to a frame.
#pragma once
#include <array>
#include <memory>

#include "core/render/method.h"
#include "core/util/stage_timer.h"
#include "core/render/frame_layout.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"

namespace sst::gpu {

class GpuRenderContext;

// The four stages' pipelines (restir_di_0 .. _3), compiled for gpu's light sampler and
// acceleration structure.
struct RestirDiPipelines {
  std::array<std::unique_ptr<ComputePipeline>, 4> stages;
};

// RestirDiHistory (core/restir/restir_di.h) on the device: the last round's first hits, final
// reservoirs and view, for temporal reuse in the next round or frame.
struct GpuRestirHistory {
  std::unique_ptr<GpuBuffer> surfaces, reservoirs, view;
  glsl::ViewParams view_params{};
  bool valid = false;
};
std::unique_ptr<RestirDiPipelines> make_restir_di_pipelines(const GpuRenderContext& gpu);

// Renders ReSTIR DI's direct light for ctx on the GPU and adds it to `frame` (add_restir_sums).
// Records the dispatches' times in frame.method_counters["gpu_ms"]["restir_di"].
void add_restir_direct(const RenderContext& ctx, const GpuRenderContext& gpu, RestirDiPipelines& pipelines,
                       StageTimer& timer, FrameOutput& frame, GpuRestirHistory& history);

}  // namespace sst::gpu
