// Options every render has, whatever the method. Method-specific parameters live in each
// method's own struct (see method_registry.h); both are serialised by their visit() lists.
#pragma once
#include <cstdint>
#include <string>

#include "core/filter/filter_params.h"
#include "core/render/direct_sampler.h"
#include "core/temporal/temporal_reuse.h"

namespace sst {

struct RenderOptions {
  std::string method = "pt";
  std::string backend = "cpu";
  int device = 0;  // Vulkan device index (sst-render --list-devices)
  // Ray queries. CPU: embree, or flat (the Vulkan backend's BVH). Vulkan: flat (that BVH traversed
  // by the shaders) or rayquery (the device's acceleration structures); embree, the default,
  // means rayquery on a GPU that has ray queries and flat elsewhere (gpu/gpu_render_context.h).
  std::string accel = "embree";
  int path_batch = 1024;          // CPU paths in flight per thread (core/pt/path_batch.h); 0: one at a time
  std::string gpu_paths = "megakernel";  // Vulkan pt: megakernel (pt.comp) or wavefront (pt_wavefront.comp)
  std::string batch_rays = "stream";  // how a batch's rays go to Embree (RayBatchApi, core/accel/embree_accel.h)
  int width = 0;   // 0: from height and the camera's aspect ratio
  int height = 0;  // 0: from width and the camera's aspect ratio
  int spp = 16;
  uint32_t seed = 0;
  bool diffuse_only = false;
  std::string light_sampler = "power";  // core/lights/light_sampler.h: uniform, power, tree, slc
  std::string light_tree = "saoh";      // core/lights/emitter_tree_build.h: saoh, morton
  std::string light_tree_distance = "centre";  // core/lights/emitter_tree.h: centre, box, mixed
  std::string direct_sampler = "nee";  // core/render/direct_sampler.h: nee, restir
  RestirDiParams restir;
  std::string camera;  // name or index; "" = the first
  int threads = 0;     // 0 = all hardware threads
  float exposure = 0.0f;  // stops, applied when writing PNG only
  // Frames in time (core/pipeline/sequence.h).
  int frames = 1;
  int frame_start = 0;
  float fps = 30.0f;
  bool temporal = false;
  TemporalParams temporal_params;
  std::string denoise = "none";
  AtrousParams atrous;
  SvgfParams svgf;
  int indirect_scale = 1;
  UpsampleParams upsample;

  template <class V>
  void visit(V&& v) {
    v("method", method, "rendering method (see --list-methods)");
    v("backend", backend, "cpu (Embree), vulkan (compute shaders) or auto (vulkan on a GPU, else cpu)");
    v("device", device, "Vulkan device index for backend vulkan/auto (see --list-devices)");
    v("accel", accel, "ray queries: on the CPU embree, or flat (the BVH the Vulkan backend traverses, for exact cross-backend comparisons); on Vulkan flat, or rayquery (the device's acceleration structures and VK_KHR_ray_query); the default (embree) is rayquery on a GPU that has it, else flat");
    v("path_batch", path_batch,
      "CPU: camera paths each thread keeps in flight, their rays traced together (0: one path at a time); the "
      "image bits are the same for every value");
    v("batch_rays", batch_rays,
      "CPU: how a batch's rays go to Embree: stream (rtcIntersect1M), packet8, packet16 (rtcIntersect8/16) or "
      "single (one rtcIntersect1 per ray); the image bits are the same for every value");
    v("gpu_paths", gpu_paths,
      "Vulkan pt: megakernel (one invocation per path, to its end) or wavefront (one dispatch per stage of the "
      "paths, their states in a buffer); the image bits are the same");
    v("width", width, "image width in pixels (0: from height and the camera's aspect ratio)");
    v("height", height, "image height in pixels (0: from width and the camera's aspect ratio)");
    v("spp", spp, "samples per pixel (pt: camera paths; many-light methods: indirect samples)");
    v("seed", seed, "random seed; the same seed gives the same image bits");
    v("diffuse_only", diffuse_only, "replace every material by Lambert baseColor/pi (+ its emission)");
    v("light_sampler", light_sampler,
      "how direct light (pt's next-event estimation, every method's direct pass, GI-1.0's cache) picks a light "
      "for a shading point: uniform, power (in proportion to power), tree (down a light tree by pbrt-v4's "
      "importance) or slc (the same tree, Yuksel's weights); light paths (VPLs) always start by power");
    v("light_tree", light_tree,
      "how the tree and slc samplers' light tree is built: saoh (top down by the surface area orientation "
      "heuristic over power, bounds and emission cones, Conty Estevez & Kulla 2018) or morton (a perfect tree "
      "over the Morton order of the lights' centres, blind to power and orientation)");
    v("light_tree_distance", light_tree_distance,
      "the distance in the tree sampler's importance: centre (to a node's box centre, at least a quarter of its "
      "bounding radius, as pbrt-v4), box (to the box, at least its bounding radius) or mixed (box outside the "
      "bounding sphere, centre within)");
    v("direct_sampler", direct_sampler,
      "how every method samples the direct light at its first hits: nee (each path's next-event estimation, "
      "MIS with BRDF sampling) or restir (ReSTIR DI: reservoirs of light samples resampled across neighbouring "
      "pixels, docs/restir.md)");
    restir.visit(v);
    v("camera", camera, "camera name or index (default: the first)");
    v("threads", threads, "CPU threads (0: all)");
    v("exposure", exposure, "exposure in stops for PNG output");
    v("frames", frames, "frames to render: a sequence when > 1 (one image per frame, out_0007.exr)");
    v("frame_start", frame_start, "index of the first frame; frame f shows the scene at time f / fps");
    v("fps", fps, "frames per second of the sequence's clock (glTF animations, key-frame paths)");
    v("temporal", temporal, "temporal reuse: reproject each pixel's history with motion vectors and accumulate");
    temporal_params.visit(v);
    v("denoise", denoise,
      "filter the indirect light: none, atrous (edge-avoiding a-trous, Dammertz 2010) or svgf (Schied 2017; "
      "accumulates temporally itself)");
    atrous.visit(v);
    svgf.visit(v);
    v("indirect_scale", indirect_scale,
      "render indirect light at 1/scale of the resolution and upsample it (joint bilateral, thesis ch. 6)");
    upsample.visit(v);
  }
};

// Throws sst::Error for impossible values (naming the option and the value), including an image
// larger than render_pixel_limit(usable_memory_bytes()).
void validate(const RenderOptions& options);

// The most pixels a render may have on a machine with `memory_bytes` to use: what fits in 3/4 of
// it at kRenderBytesPerPixel, and never more than 2^28 (16384 x 16384).
uint64_t render_pixel_limit(uint64_t memory_bytes);
// Measured peak memory per pixel of a render (colour and AOV images, G-buffer, the methods'
// per-pixel state, the written file): 16384 x 16384 pixels took about 48 GB, ~180 bytes a pixel.
constexpr uint64_t kRenderBytesPerPixel = 192;
// More threads than any machine has cores; a larger count only makes oneTBB grow its tables.
constexpr int kMaxThreads = 4096;

// The valid values of RenderOptions::backend, for error messages: "cpu, vulkan, auto".
const char* backend_names();
// Whether ReSTIR DI estimates the direct light at the first hits, so that the methods' own paths
// gather none there.
inline bool restir_direct(const RenderOptions& options) { return options.direct_sampler == "restir"; }

// The bits of the GPU passes' path flags (RENDER_* of core/render/frame_layout.h) these options set.
uint32_t render_flags(const RenderOptions& options);

// The valid values of RenderOptions::denoise: "none, atrous, svgf".
const char* denoiser_names();

}  // namespace sst
