// Sequences: per-frame seeds, key-frame paths, and temporal reuse of a static view converging as
// one render of all its samples does (per-pixel z-tests).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/pipeline/renderer.h"
#include "core/pipeline/sequence.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/key_frame_path.h"
#include "tests/test_util.h"
#include "core/util/error.h"

namespace sst {
namespace {

TEST(Sequence, FrameSeedsKeepFrameZeroAndDifferAfter) {
  EXPECT_EQ(frame_seed(7, 0), 7u);
  EXPECT_NE(frame_seed(7, 1), frame_seed(7, 2));
  EXPECT_NE(frame_seed(7, 1), frame_seed(8, 1));
  EXPECT_NE(frame_seed(7, 1), 7u);
}

TEST(Sequence, OneFrameWithoutPostProcessingIsRenderFramesImage) {
  Scene scene = load_default_scene();
  RenderOptions o;
  o.width = 24;
  o.height = 24;
  o.spp = 2;
  o.seed = 3;
  RenderResult single = render_frame(scene, o, nlohmann::json::object());
  int frames = 0;
  render_sequence(scene, {}, o, nlohmann::json::object(), true, [&](SequenceFrame& f) {
    ++frames;
    EXPECT_EQ(f.index, 0);
    EXPECT_EQ(f.result.frame.color.data, single.frame.color.data);
  });
  EXPECT_EQ(frames, 1);
}

// What the z-tests below count: 4x4-pixel blocks whose accumulated mean differs from the same
// block of an independent render of as many samples by more than z_max standard deviations. The
// variance is estimated from the spread of the sequence's frames (each draws its own seed); it
// also stands for the single render's, which, stratified over all its samples, has less. Blocks,
// not pixels, and diffuse surfaces: a path tracer's per-pixel values are too heavy-tailed for 24
// frames to estimate their variance (a firefly the frames missed makes a pixel an outlier).
struct ZTest {
  int outliers = 0;
  int blocks = 0;
  double mean_z = 0.0;
};

ZTest accumulated_vs_single(const std::string& method, const nlohmann::json& params, int frames, int spp,
                            double z_max) {
  const int size = 32, block = 4, blocks = size / block;
  Scene scene = load_default_scene();
  RenderOptions o;
  o.method = method;
  o.width = size;
  o.height = size;
  o.spp = spp;
  o.frames = frames;
  o.temporal = true;
  o.temporal_params.history_cap = frames;
  // The Cornell box's glossy surfaces make fireflies that 24 frames cannot estimate a variance of.
  o.diffuse_only = true;
  auto block_means = [&](const Image& image) {
    std::vector<double> m(blocks * blocks * 3, 0.0);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        for (int c = 0; c < 3; ++c) m[((y / block) * blocks + x / block) * 3 + c] += image.at(x, y, c) / (block * block);
    return m;
  };
  std::vector<double> sum(blocks * blocks * 3, 0.0), sum2(sum.size(), 0.0), raw_sum(size * size * 3, 0.0);
  Image accumulated;
  render_sequence(scene, {}, o, params, true, [&](SequenceFrame& f) {
    const Image* raw = nullptr;
    for (const Layer& l : f.result.frame.extra_layers)
      if (l.name == "raw") raw = &l.image;
    ASSERT_NE(raw, nullptr);
    std::vector<double> m = block_means(*raw);
    for (size_t i = 0; i < m.size(); ++i) {
      sum[i] += m[i];
      sum2[i] += m[i] * m[i];
    }
    for (size_t i = 0; i < raw_sum.size(); ++i) raw_sum[i] += raw->data[i];
    accumulated = f.result.frame.color;
  });
  // The accumulation is the running mean of the frames, to the float rounding of 24 running-mean
  // steps over values up to tens of times the mean (a frame missing would be 4% off).
  for (size_t i = 0; i < raw_sum.size(); ++i)
    EXPECT_NEAR(accumulated.data[i], raw_sum[i] / frames, 1e-3 * std::max(1.0, std::abs(raw_sum[i] / frames)));
  RenderOptions single = o;
  single.frames = 1;
  single.temporal = false;
  single.spp = spp * frames;
  single.seed = 991;
  std::vector<double> reference = block_means(render_frame(scene, single, params).frame.color);
  std::vector<double> result = block_means(accumulated);
  ZTest t;
  for (size_t i = 0; i < sum.size(); ++i) {
    double mean = sum[i] / frames;
    double var_mean = std::max(0.0, (sum2[i] - frames * mean * mean) / (frames - 1)) / frames;
    if (var_mean <= 1e-12 * std::max(1.0, mean * mean)) continue;  // nothing varies (none here)
    double z = (result[i] - reference[i]) / std::sqrt(2.0 * var_mean);
    t.mean_z += z;
    ++t.blocks;
    if (std::abs(z) > z_max) ++t.outliers;
  }
  t.mean_z /= std::max(1, t.blocks);
  std::printf("%s: %d of %d block-channels beyond |z| %.1f, mean z %.3f\n", method.c_str(), t.outliers, t.blocks, z_max,
              t.mean_z);
  return t;
}

// 192 block-channels; with 23 degrees of freedom |t| > 4 has probability 5.5e-4, 0.1 expected
// outliers. An accumulation that kept only the last frame (a variance 24 times the estimate) or
// that is biased by 3% leaves dozens; the mean z of 192 independent z's has deviation 0.07.
TEST(Sequence, TemporalAccumulationOfAStaticViewMatchesOneRenderOfAllSamplesPt) {
  ZTest t = accumulated_vs_single("pt", nlohmann::json::object(), 24, 2, 4.0);
  EXPECT_GT(t.blocks, 150);
  EXPECT_LE(t.outliers, 2) << "of " << t.blocks;
  EXPECT_LT(std::abs(t.mean_z), 0.3);
}

TEST(Sequence, TemporalAccumulationOfAStaticViewMatchesOneRenderOfAllSamplesSst) {
  // Each frame draws new VPLs; the single render has one VPL set for all its samples, whose
  // error is shared by its pixels: more VPLs than samples keep that error below the pixel noise.
  // That shared error shifts every z alike: measured mean z 0.28, hence the wider bound.
  ZTest t = accumulated_vs_single("sst", {{"vpls", 4096}}, 24, 2, 4.0);
  EXPECT_GT(t.blocks, 150);
  EXPECT_LE(t.outliers, 2) << "of " << t.blocks;
  EXPECT_LT(std::abs(t.mean_z), 0.5);
}

TEST(Sequence, KeyFramePathsTurnTheCameraAndMotionVectorsFollowIt) {
  Scene scene = load_default_scene();
  nlohmann::json paths = nlohmann::json::parse(
      R"([{"camera": "", "keys": [{"time": 0, "yaw_degrees": 0}, {"time": 1, "yaw_degrees": 30}]}])");
  std::vector<KeyFramePath> p = parse_key_frame_paths(paths, scene, "test");
  RenderOptions o;
  o.width = 32;
  o.height = 32;
  o.spp = 1;
  o.frames = 2;
  o.fps = 10.0f;  // 3 degrees per frame
  std::vector<float> mean_motion_x;
  render_sequence(scene, p, o, nlohmann::json::object(), true, [&](SequenceFrame& f) {
    const Image* motion = nullptr;
    for (const Layer& l : f.result.frame.extra_layers)
      if (l.name == "motion") motion = &l.image;
    ASSERT_NE(motion, nullptr);
    ASSERT_EQ(motion->channels, 2);
    double sx = 0.0;
    for (size_t i = 0; i < motion->pixel_count(); ++i) sx += motion->data[2 * i];
    mean_motion_x.push_back(float(sx / double(motion->pixel_count())));
  });
  ASSERT_EQ(mean_motion_x.size(), 2u);
  EXPECT_NEAR(mean_motion_x[0], 0.0f, 1e-4f);  // the first frame has no previous one
  // A turn to the left (positive yaw about up) moves the image to the right: things were further
  // left before, a negative motion, of about 3 degrees' worth of the field of view's pixels.
  float pixels_per_degree = 32.0f / (2.0f * std::atan(std::tan(scene.cameras[0].yfov / 2.0f)) * 57.29578f);
  EXPECT_LT(mean_motion_x[1], -0.5f * 3.0f * pixels_per_degree);
  EXPECT_GT(mean_motion_x[1], -1.5f * 3.0f * pixels_per_degree);
}

TEST(Sequence, KeyFramePathErrorsNameTheProblem) {
  Scene scene = load_default_scene();
  auto expect_error = [&](const char* json, const char* needle) {
    try {
      parse_key_frame_paths(nlohmann::json::parse(json), scene, "cfg.json: paths");
      ADD_FAILURE() << "no error for " << json;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("cfg.json"), std::string::npos) << e.what();
    }
  };
  expect_error(R"([{"camera": "nope", "keys": [{"time": 0}]}])", "no camera 'nope'");
  expect_error(R"([{"light": "nope", "keys": [{"time": 0}]}])", "no light 'nope'");
  expect_error(R"([{"camera": "", "keys": [{"time": 1}, {"time": 1}]}])", "does not increase");
  expect_error(R"([{"camera": "", "keys": [{"eye": [0, 0, 0]}]}])", "time");
  expect_error(R"([{"camera": "", "keys": [{"time": 0, "eye": [0, 0]}]}])", "eye");
  expect_error(R"([{"camera": "", "keys": [{"time": 0, "eye": [0, 0, 0], "translate": [0, 0, 0]}]}])", "both");
  expect_error(R"([{"camera": "", "keys": []}])", "keys");
  expect_error(R"([{"camera": "", "keys": [{"time": 0, "zoom": 2}]}])", "zoom");
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// The mean of the last of 16 frames (1 spp each, a static view, the path tracer), summed over four
// seeds, through a denoiser (`svgf` sets its parameters), relative to the temporally accumulated
// frames without one: the same samples, filtered or not. Edge-avoiding filters move light between
// pixels but should not create or lose it. One seed is not enough to tell: SVGF's mean moves by
// +-3% from seed to seed (measured over seeds 0-4), its fed-back history amplifying a few fireflies.
double denoised_mean_ratio(const Scene& scene, const std::string& denoiser, const SvgfParams& svgf = {}) {
  auto last_mean = [&](const std::string& d) {
    double sum = 0.0;
    for (uint32_t seed = 0; seed < 4; ++seed) {
      Scene posed = scene;
      RenderOptions o;
      o.width = 96;
      o.spp = 1;
      o.frames = 16;
      o.temporal = true;
      o.denoise = d;
      o.svgf = svgf;
      o.seed = seed;
      double last = 0.0;
      render_sequence(posed, {}, o, nlohmann::json::object(), true, [&](SequenceFrame& f) {
        last = 0.0;
        for (float v : f.result.frame.color.data) last += v;
      });
      sum += last;
    }
    return sum;
  };
  return last_mean(denoiser) / last_mean("none");
}

TEST(Sequence, DenoisersKeepTheMeanOfTheBreakfastRoom) {
  auto path = test::shared_scene("breakfast-room/breakfast-room.gltf");
  if (path.empty() || !std::filesystem::exists(path)) GTEST_SKIP() << "../shared/scenes/breakfast-room absent";
  Scene scene = load_gltf(path.string());
  SvgfParams no_luminance_weights;
  no_luminance_weights.sigma_l = 1000.0f;
  double atrous = denoised_mean_ratio(scene, "atrous"), svgf = denoised_mean_ratio(scene, "svgf"),
         svgf_geometric = denoised_mean_ratio(scene, "svgf", no_luminance_weights);
  std::printf("breakfast room, 16 frames of 1 spp, 4 seeds: mean ratio atrous %.4f, svgf %.4f, svgf with sigma_l 1000 %.4f\n",
              atrous, svgf, svgf_geometric);
  // Measured (96 px, pt, seeds 0-3): atrous 0.9983, svgf 0.9758, svgf with sigma_l 1000 0.9989.
  // SVGF loses 2.4%: its luminance weights are asymmetric (a pixel's tolerance comes from its own
  // variance), so a firefly shares its light with dimmer neighbours that do not take it, and the
  // feedback of filtered light into the history compounds that every frame; without luminance
  // weights it keeps the mean. Its bound holds what is measured with room for another render; the
  // last bound catches an unstable feedback loop (an earlier albedo divisor tripled the mean).
  EXPECT_NEAR(atrous, 1.0, 0.005);
  EXPECT_NEAR(svgf, 1.0, 0.04);
  EXPECT_NEAR(svgf_geometric, 1.0, 0.01);
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// RTSLC interleaves its cut samples over time: the same seed renders another slot of each tile in
// the next frame, and nothing changes without interleaving.
TEST(Sequence, RtslcInterleavesItsCutNodesAcrossFrames) {
  Scene scene = load_default_scene();
  auto image = [&](int interleave, int frame) {
    RenderOptions o;
    o.method = "rtslc";
    o.width = 24;
    o.height = 24;
    o.spp = 1;
    FrameRenderer renderer(o, {{"vpls", 2000}, {"interleave", interleave}}, true);
    StageTimer t;
    renderer.prepare(scene, t);
    return renderer.render(scene, scene.cameras[0], 5, 0, 0, frame).frame.indirect.data;
  };
  EXPECT_EQ(image(1, 0), image(1, 1));
  EXPECT_NE(image(2, 0), image(2, 1));
  EXPECT_EQ(image(2, 0), image(2, 4));  // r^2 = 4 slots: frame 4 takes frame 0's again
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// The previous frame resampled bilinearly at each pixel's motion vector predicts the current frame
// (a turning camera over the Cornell box, many samples so that noise does not hide the shift):
// far better than the previous frame as it is, or read at the opposite motion.
TEST(Sequence, MotionVectorsOfATurningCameraPredictTheNextFrame) {
  Scene scene = load_default_scene();
  std::vector<KeyFramePath> p = parse_key_frame_paths(
      nlohmann::json::parse(R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 30}]}])"), scene, "test");
  RenderOptions o;
  o.width = 64;
  o.height = 64;
  o.spp = 64;
  o.frames = 2;
  o.fps = 10.0f;  // 3 degrees a frame: about 2.5 pixels
  o.diffuse_only = true;
  std::vector<Image> color, motion;
  render_sequence(scene, p, o, nlohmann::json::object(), true, [&](SequenceFrame& f) {
    color.push_back(f.result.frame.color);
    for (const Layer& l : f.result.frame.extra_layers)
      if (l.name == "motion") motion.push_back(l.image);
  });
  ASSERT_EQ(motion.size(), 2u);
  auto warp_error = [&](float sign) {
    double e = 0.0;
    int n = 0;
    for (int y = 4; y < 60; ++y)
      for (int x = 4; x < 60; ++x) {
        float fx = float(x) + sign * motion[1].at(x, y, 0), fy = float(y) + sign * motion[1].at(x, y, 1);
        int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        if (x0 < 0 || y0 < 0 || x0 + 1 >= 64 || y0 + 1 >= 64) continue;
        float tx = fx - float(x0), ty = fy - float(y0);
        for (int c = 0; c < 3; ++c) {
          float v = (1 - tx) * (1 - ty) * color[0].at(x0, y0, c) + tx * (1 - ty) * color[0].at(x0 + 1, y0, c) +
                    (1 - tx) * ty * color[0].at(x0, y0 + 1, c) + tx * ty * color[0].at(x0 + 1, y0 + 1, c);
          e += double(v - color[1].at(x, y, c)) * (v - color[1].at(x, y, c));
          ++n;
        }
      }
    return std::sqrt(e / n);
  };
  double forward = warp_error(1.0f), none = warp_error(0.0f), backward = warp_error(-1.0f);
  std::printf("previous frame vs current, RMSE: at the motion vectors %.4f, unmoved %.4f, opposite %.4f\n", forward, none,
              backward);
  EXPECT_LT(forward, 0.6 * none);
  EXPECT_LT(forward, 0.6 * backward);
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// A sequence continued from the state saved after frame k renders the frames the uninterrupted
// sequence renders, bit for bit; a state file cut short is refused, naming the file.
TEST(Sequence, ContinuesFromASavedStateWithTheSameFrames) {
  Scene scene = load_default_scene();
  RenderOptions o;
  o.method = "sst";
  o.width = 20;
  o.height = 16;
  o.spp = 1;
  o.frames = 4;
  o.temporal = true;
  o.denoise = "svgf";
  const nlohmann::json params = {{"vpls", 300}};
  std::vector<KeyFramePath> paths =
      parse_key_frame_paths(nlohmann::json::parse(R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 30}]}])"),
                            scene, "paths");
  std::vector<std::vector<float>> whole;
  Scene posed = scene;
  render_sequence(posed, paths, o, params, true, [&](SequenceFrame& f) { whole.push_back(f.result.frame.color.data); });

  const std::string file = (test::temp_dir() / "state.bin").string();
  posed = scene;
  SequenceState state;
  render_sequence(posed, paths, o, params, true, [&](SequenceFrame& f) {
    if (f.index == 1) write_sequence_state(file, state);
  }, &state);
  SequenceState saved = read_sequence_state(file);
  EXPECT_EQ(saved.next, 2);
  EXPECT_EQ(saved.temporal.size(), size_t(o.width * o.height));
  posed = scene;
  std::vector<std::vector<float>> continued;
  render_sequence(posed, paths, o, params, true, [&](SequenceFrame& f) { continued.push_back(f.result.frame.color.data); },
                  &saved);
  ASSERT_EQ(continued.size(), 2u);
  EXPECT_EQ(continued[0], whole[2]);
  EXPECT_EQ(continued[1], whole[3]);

  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 8);
  try {
    read_sequence_state(file);
    ADD_FAILURE() << "a truncated state was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sst
