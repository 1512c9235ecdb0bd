#include "gpu/temporal_pass.h"

#include "core/util/error.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"

namespace sst::gpu {

TemporalHistory temporal_accumulate(const VulkanContext& context, const std::vector<TemporalInput>& input,
                                    const std::vector<TemporalTexel>& history, const TemporalPush& push) {
  if (input.size() != size_t(push.width) * push.height) throw Error("temporal_accumulate: input size mismatch");
  TemporalHistory result;
  if (input.empty()) return result;
  // The first frame reads a history that matches nothing (depth 0), so it starts every average.
  const std::vector<TemporalTexel> empty(history.size() == input.size() ? 0 : input.size(), TemporalTexel{});
  auto input_buffer = upload_buffer(context, input, "temporal input");
  auto history_buffer = upload_buffer(context, history.size() == input.size() ? history : empty, "temporal history");
  auto next = make_buffer(context, input.size(), sizeof(TemporalTexel), "temporal history");
  ComputePipeline pipeline(context, "temporal_accumulate", 3, sizeof(TemporalPush));
  result.gpu_ms = pipeline.dispatch({input_buffer.get(), history_buffer.get(), next.get()}, &push,
                                    (push.width + 7u) / 8u, (push.height + 7u) / 8u);
  result.texels.resize(input.size());
  next->download(std::span<TemporalTexel>(result.texels));
  return result;
}

}  // namespace sst::gpu
