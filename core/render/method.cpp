#include "core/render/method.h"

#include "core/util/error.h"

namespace sst {

FrameOutput Method::render_vulkan(const RenderContext& context, StageTimer&) {
  throw Error("method '" + context.options.method + "' has no Vulkan port yet; use --backend cpu");
}

}  // namespace sst
