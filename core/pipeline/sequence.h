// Frames in time: a sequence of frames of one scene, posed per frame by its animation and key-frame
// paths, each rendered with fresh random numbers (new VPLs, rebuilt trees: the papers' dynamic
// setting), then reused temporally, denoised and upsampled as RenderOptions ask. A single frame
// with none of these is exactly render_frame's image.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/image/image.h"
#include "core/pipeline/renderer.h"
#include "core/pipeline/sequence_state.h"
#include "core/render/render_options.h"
#include "core/scene/key_frame_path.h"
#include "core/scene/scene.h"

namespace sst {

struct SequenceFrame {
  int index = 0;        // absolute frame index (frame_start + position in the sequence)
  double time = 0.0;    // seconds: index / fps
  // result.frame.color is the frame's output (after temporal reuse, denoising and upsampling);
  // its AOVs and extra layers include "motion" (in a sequence or with temporal reuse) and "raw"
  // (the method's image before post-processing, when post-processing changed it). result.timer
  // holds the setup stages the frame paid (when posing moved geometry or lights), the method's
  // stages and those of post-processing: "direct" (half-resolution indirect only), "upsample",
  // "gbuffer" (the pixel centres' G-buffer and motion, core/render/centre_gbuffer.h), "temporal",
  // "denoise", and "post_convert" (the host's conversions between them).
  RenderResult result;
};

// Whether `options` ask for more than render_frame gives: several frames, temporal reuse, a
// denoiser or half-resolution indirect light (then every frame also gets the pixel-centre G-buffer
// and its motion layer).
bool renders_sequence(const RenderOptions& options);

// The seed of frame `index`: the run's seed for frame 0, a hash of both after, so every frame
// draws its own random numbers and a frame's image does not depend on where the sequence began.
uint32_t frame_seed(uint32_t seed, int index);

// Renders frames options.frame_start .. frame_start + frames - 1 of `scene` (posed in place),
// handing each to `on_frame` as soon as it is finished (frames are not kept: write them there).
// With `state`, the sequence continues from state->next with its history, and *state is the
// sequence's state after each frame by the time on_frame sees that frame (save it there to resume).
void render_sequence(Scene& scene, const std::vector<KeyFramePath>& paths, const RenderOptions& options,
                     const nlohmann::json& method_params, bool quiet,
                     const std::function<void(SequenceFrame&)>& on_frame, SequenceState* state = nullptr);

}  // namespace sst
