#include "core/render/render_options.h"

#include <cmath>

#include "core/util/error.h"

namespace sst {

const char* backend_names() { return "cpu, vulkan, auto"; }
const char* denoiser_names() { return "none, atrous, svgf"; }

void validate(const RenderOptions& o) {
  if (o.width < 0 || o.height < 0) throw Error("width and height must be >= 0");
  if (int64_t(o.width) * o.height > (int64_t(1) << 28)) throw Error("image of " + std::to_string(o.width) + "x" + std::to_string(o.height) + " pixels is too large");
  if (o.spp < 1) throw Error("spp must be >= 1 (got " + std::to_string(o.spp) + ")");
  if (o.device < 0) throw Error("device must be >= 0 (got " + std::to_string(o.device) + ")");
  if (o.accel != "embree" && o.accel != "flat")
    throw Error("unknown accel '" + o.accel + "' (valid: embree, flat)");
  if (o.threads < 0) throw Error("threads must be >= 0");
  if (!std::isfinite(o.exposure)) throw Error("exposure must be finite");
  if (o.frames < 1) throw Error("frames must be >= 1 (got " + std::to_string(o.frames) + ")");
  if (o.frame_start < 0) throw Error("frame_start must be >= 0 (got " + std::to_string(o.frame_start) + ")");
  if (!(o.fps > 0.0f) || !std::isfinite(o.fps)) throw Error("fps must be finite and > 0");
  validate(o.temporal_params);
  validate(o.atrous);
  validate(o.svgf);
  validate(o.upsample);
  if (o.denoise != "none" && o.denoise != "atrous" && o.denoise != "svgf")
    throw Error("unknown denoise '" + o.denoise + "' (valid: " + denoiser_names() + ")");
  if (o.indirect_scale < 1 || o.indirect_scale > 16)
    throw Error("indirect_scale must be in 1..16 (got " + std::to_string(o.indirect_scale) + ")");
  // Only the name is checked here; resolve_backend (in the pipeline) decides what runs.
  if (o.backend != "cpu" && o.backend != "vulkan" && o.backend != "auto")
    throw Error("unknown backend '" + o.backend + "' (valid: " + backend_names() + ")");
}

}  // namespace sst
