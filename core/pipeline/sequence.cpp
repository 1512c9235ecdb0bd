#include "core/pipeline/sequence.h"

#include <chrono>

#include "core/filter/filters.h"
#include "core/pipeline/method_registry.h"
#include "core/render/camera.h"
#include "core/render/centre_gbuffer.h"
#include "core/rng/hash_rng.h"
#include "core/scene/animation.h"
#include "core/temporal/temporal_reuse.h"
#include "core/util/error.h"

#ifdef SST_HAVE_VULKAN
#include "gpu/filter_pass.h"
#include "gpu/gpu_render_context.h"
#include "gpu/temporal_pass.h"
#endif

namespace sst {

bool renders_sequence(const RenderOptions& o) {
  return o.frames > 1 || o.temporal || o.denoise != "none" || o.indirect_scale > 1;
}

uint32_t frame_seed(uint32_t seed, int index) {
  if (index == 0) return seed;
  return pcg_hash(seed ^ pcg_hash(uint32_t(index) * 0x9E3779B9u));
}

namespace {

Image sum(const Image& a, const Image& b) {
  Image out = a;
  for (size_t i = 0; i < out.data.size(); ++i) out.data[i] += b.data[i];
  return out;
}

void add_stages(StageTimer& to, const StageTimer& from, const std::string& prefix = "") {
  for (const auto& [stage, ms] : from.stages()) to.add(prefix + stage, ms);
}

// The post-processing stages on the backend the frame rendered on: the Vulkan ones run the same
// kernels as the CPU's (gpu/temporal_pass.h, gpu/filter_pass.h). A stage's time is the GPU time of
// its dispatches on Vulkan (the uploads and readbacks around them go to "<stage>_transfer": they
// exist only because the frame comes back to the CPU between stages) and the wall time on the CPU.
class PostStages {
 public:
  PostStages(const FrameRenderer& renderer, StageTimer& timer) : renderer_(renderer), timer_(timer) {}

  // Defined before its callers: they deduce their return type from it.
  template <class F>
  auto on_gpu(const std::string& stage, F&& f) {
    auto start = std::chrono::steady_clock::now();
    auto result = f();
    double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    timer_.add(stage, result.gpu_ms);
    timer_.add(stage + "_transfer", std::max(0.0, wall - result.gpu_ms));
    return result;
  }


  std::vector<TemporalTexel> temporal(const std::vector<TemporalInput>& input,
                                      const std::vector<TemporalTexel>& history, const TemporalPush& push) {
#ifdef SST_HAVE_VULKAN
    if (const gpu::GpuRenderContext* g = renderer_.gpu())
      return on_gpu("temporal", [&] { return gpu::temporal_accumulate(g->vulkan(), input, history, push); }).texels;
#endif
    return timer_.time("temporal", [&] { return temporal_accumulate(input, history, push); });
  }

  Image atrous(const Image& color, const Image& depth, const Image& normal, const AtrousParams& p) {
#ifdef SST_HAVE_VULKAN
    if (const gpu::GpuRenderContext* g = renderer_.gpu())
      return on_gpu("denoise", [&] { return gpu::atrous_filter(g->vulkan(), color, depth, normal, p); }).image;
#endif
    return timer_.time("denoise", [&] { return atrous_filter(color, depth, normal, p); });
  }

  SvgfSpatialResult svgf(const TemporalImages& t, const Image& depth, const Image& normal, const SvgfParams& p) {
#ifdef SST_HAVE_VULKAN
    if (const gpu::GpuRenderContext* g = renderer_.gpu())
      return on_gpu("denoise", [&] {
        return gpu::svgf_spatial(g->vulkan(), t.indirect, t.indirect_moments, t.frames, depth, normal, p);
      });
#endif
    return timer_.time("denoise",
                       [&] { return svgf_spatial(t.indirect, t.indirect_moments, t.frames, depth, normal, p); });
  }

  Image upsample(const Image& low, const CentreGBuffer& low_g, const CentreGBuffer& g, const UpsampleParams& p) {
#ifdef SST_HAVE_VULKAN
    if (const gpu::GpuRenderContext* gc = renderer_.gpu())
      return on_gpu("upsample", [&] {
               return gpu::joint_bilateral_upsample(gc->vulkan(), low, low_g.depth, low_g.normal, g.depth, g.normal, p);
             }).image;
#endif
    return timer_.time("upsample",
                       [&] { return joint_bilateral_upsample(low, low_g.depth, low_g.normal, g.depth, g.normal, p); });
  }

 private:
  [[maybe_unused]] const FrameRenderer& renderer_;  // read only where the GPU is built in
  StageTimer& timer_;
};

class SequenceRunner {
 public:
  SequenceRunner(Scene& scene, const std::vector<KeyFramePath>& paths, const RenderOptions& options,
                 const nlohmann::json& method_params, bool quiet, SequenceState& state, bool keep_histories)
      : scene_(scene), paths_(paths), renderer_(options, method_params, quiet), options_(renderer_.options()),
        keep_histories_(keep_histories), state_(state) {
    camera_index_ = scene.find_camera(options_.camera);
    if (camera_index_ < 0) select_camera(scene, options_.camera);  // throws, listing the cameras
    resolve_resolution(scene.cameras[size_t(camera_index_)], options_.width, options_.height);
    validate(options_);
    reuse_ = options_.temporal || options_.denoise == "svgf";
    gbuffer_ = renders_sequence(options_);
  }

  SequenceFrame frame(int position) {
    SequenceFrame out;
    out.index = options_.frame_start + position;
    out.time = double(out.index) / double(options_.fps);
    StageTimer timer;
    PoseChange moved;
    if (scene_.animation) moved = scene_.animation->pose(scene_, out.time);
    moved.lights = apply_key_frame_paths(paths_, scene_, out.time) || moved.lights;
    // Cameras are read per frame; geometry and lights are built into the renderer.
    if (!prepared_ || moved.geometry || moved.lights) renderer_.prepare(scene_, timer);
    // A sequence continued from a checkpoint gets its ReSTIR and method histories back, posed anew
    // if this frame's pose differs from the rest pose (for an animation that moves every frame, as
    // the uninterrupted run would have found).
    if (!prepared_ && state_.has_previous) renderer_.restore_histories(state_, moved.geometry || moved.lights);
    prepared_ = true;
    const Camera& camera = scene_.cameras[size_t(camera_index_)];
    const uint32_t seed = frame_seed(options_.seed, out.index);
    const int w = options_.width, h = options_.height;
    glsl::ViewParams view = view_params(PinholeCamera(camera, w, h), w, h, 0);
    if (!state_.has_previous) {
      state_.positions = scene_.positions;
      state_.view = view;
    }
    CentreGBuffer g;
    if (gbuffer_)
      g = timer.time("gbuffer",
                     [&] { return centre_gbuffer(renderer_.accel(), scene_, state_.positions, view, state_.view); });
    PostStages post(renderer_, timer);
    if (options_.indirect_scale > 1) {
      out.result = render_split(camera, seed, out.index, g, timer, post);
    } else {
      out.result = renderer_.render(scene_, camera, seed, w, h, out.index);
      add_stages(timer, out.result.timer);
    }
    if (gbuffer_) post_process(out.result.frame, g, post, timer);
    out.result.timer = timer;
    out.result.options = options_;
    out.result.options.seed = seed;
    state_.has_previous = true;
    state_.view = view;
    // Only posing moves vertices; a static scene's stay those of the first frame.
    if (moved.geometry) state_.positions = scene_.positions;
    if (keep_histories_) renderer_.save_histories(state_);
    state_.next = position + 1;
    return out;
  }

 private:
  // A frame whose indirect light renders at 1/indirect_scale of the resolution: the direct light at
  // full resolution (the path tracer without bounces: every method's direct pass), the method at
  // low resolution for its indirect light, which joint bilateral upsampling brings to full
  // resolution, guided by the two frames' pixel-centre G-buffers. Its stages: the direct render's
  // as "direct_<stage>", the method's own, "gbuffer_low" and "upsample".
  RenderResult render_split(const Camera& camera, uint32_t seed, int frame, const CentreGBuffer& g,
                            StageTimer& timer, PostStages& post) {
    const int s = options_.indirect_scale;
    const int lw = std::max(1, options_.width / s), lh = std::max(1, options_.height / s);
    RenderResult full = renderer_.render_direct(scene_, camera, seed);
    add_stages(timer, full.timer, "direct_");
    RenderResult low = renderer_.render(scene_, camera, seed, lw, lh, frame, false);
    add_stages(timer, low.timer);
    glsl::ViewParams low_view = view_params(PinholeCamera(camera, lw, lh), lw, lh, 0);
    CentreGBuffer low_g = timer.time("gbuffer_low", [&] {
      return centre_gbuffer(renderer_.accel(), scene_, scene_.positions, low_view, low_view);
    });
    // Each resolution's light is demodulated and remodulated by the mean albedo of its own samples.
    Image low_light = timer.time("post_convert", [&] { return demodulate(low.frame.indirect, low.frame.albedo); });
    Image up = post.upsample(low_light, low_g, g, options_.upsample);
    RenderResult result = std::move(full);
    result.method_params = low.method_params;
    timer.time("post_convert", [&] {
      result.frame.indirect = remodulate(up, result.frame.albedo);
      result.frame.color = sum(result.frame.direct, result.frame.indirect);
    });
    result.frame.counters += low.frame.counters;
    result.frame.method_counters = low.frame.method_counters;
    result.frame.extra_layers.clear();
    return result;
  }

  // Temporal reuse and denoising of the frame's light, in place; the frame keeps its unfiltered
  // image as the layer "raw" and gains "motion". Light is demodulated by the mean albedo of the
  // pixel's samples and remodulated by the same albedo, or by its temporal average where the
  // history is reused (core/temporal/temporal_layout.h says why not the pixel centre's), so that
  // what no filter changed comes back unchanged. The host's conversions between the stages
  // (demodulation, packing the per-pixel inputs, reading the history back into images) are timed
  // as "post_convert".
  void post_process(FrameOutput& f, const CentreGBuffer& g, PostStages& post, StageTimer& timer) {
    const int w = f.color.width, h = f.color.height;
    Image raw = f.color;
    Image direct, indirect, albedo;
    TemporalImages history;
    if (reuse_) {
      std::vector<TemporalInput> input = timer.time("post_convert", [&] {
        return temporal_inputs(f.direct, f.indirect, f.albedo, g.depth, g.normal, g.motion, g.previous_depth);
      });
      state_.temporal = post.temporal(input, state_.temporal, temporal_push(options_.temporal_params, w, h));
      timer.time("post_convert", [&] {
        history = temporal_images(state_.temporal, w, h);
        direct = history.direct;
        indirect = history.indirect;
        albedo = history.albedo;
      });
    } else {
      timer.time("post_convert", [&] {
        direct = demodulate(f.direct, f.albedo);
        indirect = demodulate(f.indirect, f.albedo);
        albedo = f.albedo;
      });
    }
    if (options_.denoise == "atrous") {
      indirect = post.atrous(indirect, g.depth, g.normal, options_.atrous);
    } else if (options_.denoise == "svgf") {
      SvgfSpatialResult s = post.svgf(history, g.depth, g.normal, options_.svgf);
      indirect = s.filtered;
      // SVGF's feedback: the history continues from the first a-trous level's output.
      timer.time("post_convert", [&] { set_temporal_indirect(state_.temporal, s.level1, albedo); });
      f.extra_layers.push_back({"variance", s.variance});
    }
    if (reuse_ || options_.denoise != "none") {
      timer.time("post_convert", [&] {
        f.direct = remodulate(direct, albedo);
        f.indirect = remodulate(indirect, albedo);
        f.color = sum(f.direct, f.indirect);
      });
      f.extra_layers.push_back({"raw", raw});
    }
    f.extra_layers.push_back({"motion", g.motion});
  }

  Scene& scene_;
  const std::vector<KeyFramePath>& paths_;
  FrameRenderer renderer_;
  RenderOptions options_;
  int camera_index_ = 0;
  bool reuse_ = false, gbuffer_ = false, prepared_ = false;
  bool keep_histories_;  // the caller keeps the state to resume from it: save the histories into it
  SequenceState& state_;
};

}  // namespace

void render_sequence(Scene& scene, const std::vector<KeyFramePath>& paths, const RenderOptions& options,
                     const nlohmann::json& method_params, bool quiet,
                     const std::function<void(SequenceFrame&)>& on_frame, SequenceState* state) {
  SequenceState own;
  SequenceState& s = state ? *state : own;
  if (s.next > options.frames) throw Error("a sequence state at frame " + std::to_string(s.next) + " of " +
                                           std::to_string(options.frames));
  SequenceRunner runner(scene, paths, options, method_params, quiet, s,
                        state != nullptr && find_method(options.method).resumable);
  for (int i = s.next; i < options.frames; ++i) {
    SequenceFrame frame = runner.frame(i);
    on_frame(frame);
  }
}

}  // namespace sst
