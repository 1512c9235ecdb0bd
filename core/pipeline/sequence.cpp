#include "core/pipeline/sequence.h"

#include <tbb/parallel_for.h>

#include "core/render/camera.h"
#include "core/render/centre_gbuffer.h"
#include "core/rng/hash_rng.h"
#include "core/temporal/temporal_reuse.h"
#include "core/util/error.h"

namespace sst {

uint32_t frame_seed(uint32_t seed, int index) {
  if (index == 0) return seed;
  return pcg_hash(seed ^ pcg_hash(uint32_t(index) * 0x9E3779B9u));
}

namespace {

// Illumination back to radiance: the inverse of the demodulation of temporal_inputs.
Image remodulate(const Image& illumination, const Image& albedo) {
  Image out(illumination.width, illumination.height, 3);
  tbb::parallel_for(0, illumination.height, [&](int y) {
    for (int x = 0; x < illumination.width; ++x)
      out.set_rgb(x, y, illumination.rgb(x, y) * demodulation_albedo(albedo.rgb(x, y)));
  });
  return out;
}

Image sum(const Image& a, const Image& b) {
  Image out = a;
  for (size_t i = 0; i < out.data.size(); ++i) out.data[i] += b.data[i];
  return out;
}

// The state one frame hands the next.
struct History {
  bool valid = false;
  std::vector<vec3> positions;  // the scene's vertices as the frame saw them
  glsl::ViewParams view{};
  std::vector<TemporalTexel> temporal;
};

class SequenceRunner {
 public:
  SequenceRunner(Scene& scene, const std::vector<KeyFramePath>& paths, const RenderOptions& options,
                 const nlohmann::json& method_params, bool quiet)
      : scene_(scene), paths_(paths), renderer_(options, method_params, quiet), options_(renderer_.options()) {
    camera_index_ = scene.find_camera(options_.camera);
    if (camera_index_ < 0) select_camera(scene, options_.camera);  // throws, listing the cameras
    resolve_resolution(scene.cameras[size_t(camera_index_)], options_.width, options_.height);
    validate(options_);
    reuse_ = options_.temporal || options_.denoise == "svgf";
    gbuffer_ = reuse_ || options_.frames > 1;
    if (options_.denoise != "none") throw Error("denoise '" + options_.denoise + "' is not available yet");
    if (options_.indirect_scale > 1) throw Error("indirect_scale > 1 is not available yet");
  }

  SequenceFrame frame(int position) {
    SequenceFrame out;
    out.index = options_.frame_start + position;
    out.time = double(out.index) / double(options_.fps);
    StageTimer setup;
    bool lights_moved = apply_key_frame_paths(paths_, scene_, out.time);
    if (position == 0 || lights_moved) renderer_.prepare(scene_, setup);
    const Camera& camera = scene_.cameras[size_t(camera_index_)];
    uint32_t seed = frame_seed(options_.seed, out.index);
    out.result = renderer_.render(scene_, camera, seed, options_.width, options_.height);
    StageTimer timer = setup;
    for (const auto& [stage, ms] : out.result.timer.stages()) timer.add(stage, ms);
    post_process(out.result, timer, camera);
    out.result.timer = timer;
    out.result.options = options_;
    out.result.options.seed = seed;
    return out;
  }

 private:
  void post_process(RenderResult& result, StageTimer& timer, const Camera& camera) {
    FrameOutput& f = result.frame;
    const int w = f.color.width, h = f.color.height;
    glsl::ViewParams view = view_params(PinholeCamera(camera, w, h), w, h, 0);
    if (!history_.valid) {
      history_.positions = scene_.positions;
      history_.view = view;
    }
    if (gbuffer_) {
      CentreGBuffer g = timer.time("gbuffer", [&] {
        return centre_gbuffer(renderer_.accel(), scene_, history_.positions, view, history_.view);
      });
      if (reuse_) {
        std::vector<TemporalInput> input =
            temporal_inputs(f.direct, f.indirect, g.albedo, g.depth, g.normal, g.motion, g.previous_depth);
        TemporalPush push = temporal_push(options_.temporal_params, w, h);
        history_.temporal = timer.time("temporal", [&] { return temporal_accumulate(input, history_.temporal, push); });
        Image direct = temporal_images(history_.temporal, w, h, true).illumination;
        Image indirect = temporal_images(history_.temporal, w, h, false).illumination;
        f.extra_layers.push_back({"raw", f.color});
        f.direct = remodulate(direct, g.albedo);
        f.indirect = remodulate(indirect, g.albedo);
        f.color = sum(f.direct, f.indirect);
      }
      f.extra_layers.push_back({"motion", g.motion});
    }
    history_.valid = true;
    history_.view = view;
    // Only animated geometry changes the vertices; a static scene's stay those of the first frame.
    if (scene_.positions.size() != history_.positions.size() || scene_.positions != history_.positions)
      history_.positions = scene_.positions;
  }

  Scene& scene_;
  const std::vector<KeyFramePath>& paths_;
  FrameRenderer renderer_;
  RenderOptions options_;
  int camera_index_ = 0;
  bool reuse_ = false, gbuffer_ = false;
  History history_;
};

}  // namespace

void render_sequence(Scene& scene, const std::vector<KeyFramePath>& paths, const RenderOptions& options,
                     const nlohmann::json& method_params, bool quiet,
                     const std::function<void(SequenceFrame&)>& on_frame) {
  SequenceRunner runner(scene, paths, options, method_params, quiet);
  for (int i = 0; i < options.frames; ++i) {
    SequenceFrame frame = runner.frame(i);
    on_frame(frame);
  }
}

}  // namespace sst
