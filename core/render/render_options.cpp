#include "core/render/render_options.h"

#include <algorithm>
#include <cmath>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/frame_layout.h"
#include "core/util/machine_info.h"

#include "core/util/error.h"

namespace sst {

const char* backend_names() { return "cpu, vulkan, auto"; }
const char* denoiser_names() { return "none, atrous, svgf"; }

uint32_t render_flags(const RenderOptions& o) {
  return (o.diffuse_only ? RENDER_DIFFUSE_ONLY : 0u) | (o.direct_sampler == "restir" ? RENDER_RESTIR_DIRECT : 0u);
}

uint64_t render_pixel_limit(uint64_t memory_bytes) {
  return std::min<uint64_t>(memory_bytes / 4 * 3 / kRenderBytesPerPixel, uint64_t(1) << 28);
}

void validate(const RenderOptions& o) {
  if (o.width < 0 || o.height < 0) throw Error("width and height must be >= 0");
  const uint64_t pixels = uint64_t(o.width) * uint64_t(o.height);
  const uint64_t memory = usable_memory_bytes();
  if (pixels > render_pixel_limit(memory)) {
    // Checked before anything is allocated: the render would otherwise be killed for memory
    // (or take the machine down) after minutes of work.
    auto gib = [](uint64_t bytes) { return std::to_string((bytes + (uint64_t(1) << 29)) >> 30); };
    throw Error("image of " + std::to_string(o.width) + "x" + std::to_string(o.height) + " pixels is too large: it needs about " +
                gib(pixels * kRenderBytesPerPixel) + " GiB, this machine has " + gib(memory) + " GiB (at most " +
                std::to_string(render_pixel_limit(memory)) + " pixels)");
  }
  if (o.spp < 1) throw Error("spp must be >= 1 (got " + std::to_string(o.spp) + ")");
  if (o.device < 0) throw Error("device must be >= 0 (got " + std::to_string(o.device) + ")");
  parse_light_sampler(o.light_sampler);  // throws for an unknown name
  parse_emitter_tree_build(o.light_tree);
  parse_emitter_distance(o.light_tree_distance);
  if (o.direct_sampler != "nee" && o.direct_sampler != "restir")
    throw Error("unknown direct_sampler '" + o.direct_sampler + "' (valid: " + direct_sampler_names() + ")");
  validate(o.restir);
  if (o.accel != "embree" && o.accel != "flat" && o.accel != "rayquery")
    throw Error("unknown accel '" + o.accel + "' (valid: embree, flat, rayquery)");
  if (o.path_batch < 0 || o.path_batch > (1 << 20))
    throw Error("path_batch must be in 0..1048576 (got " + std::to_string(o.path_batch) + ")");
  parse_ray_batch_api(o.batch_rays);
  if (o.gpu_paths != "megakernel" && o.gpu_paths != "wavefront")
    throw Error("unknown gpu_paths '" + o.gpu_paths + "' (valid: megakernel, wavefront)");
  if (o.threads < 0 || o.threads > kMaxThreads)
    throw Error("threads must be in 0.." + std::to_string(kMaxThreads) + " (got " + std::to_string(o.threads) + ")");
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
