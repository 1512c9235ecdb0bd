// ReSTIR DI (--direct-sampler restir, core/restir/): the unbiased combination converges to the
// path tracer's direct light (Welch t per block over seeds) on a scene of many lights of every
// kind and on the glossy Cornell box, for every light sampler; the biased one's darkening is
// measured and bounded; the methods' own paths gather no direct light under it, so nothing is
// counted twice; bad parameters are errors that name them.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/pipeline/renderer.h"
#include "core/pipeline/sequence.h"
#include "core/scene/key_frame_path.h"
#include "core/scene/scene.h"
#include "core/scene/default_scene.h"
#include "core/util/error.h"
#include "tests/analytic_scenes.h"
#include "tests/stat_util.h"

namespace sst {
namespace {

constexpr int kSize = 32, kBlock = 4, kSeeds = 12;

RenderOptions options(const std::string& method, const std::string& sampler, bool diffuse_only, int spp,
                      uint32_t seed) {
  RenderOptions o;
  o.method = method;
  o.width = o.height = kSize;
  o.spp = spp;
  o.seed = seed;
  o.diffuse_only = diffuse_only;
  o.light_sampler = sampler;
  return o;
}

test::SeedBlockMeans direct_blocks(const Scene& scene, const RenderOptions& base, const nlohmann::json& params) {
  test::SeedBlockMeans s(kSize, kSize, kBlock);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o = base;
    o.seed = uint32_t(500 + seed);
    s.add(render_frame(scene, o, params).frame.direct);
  }
  return s;
}

struct Variant {
  const char* name;
  const char* sampler;
  RestirDiParams restir;
};

RestirDiParams restir_params(int passes, int brdf, const char* combine) {
  RestirDiParams p;
  p.temporal = false;
  p.spatial_passes = passes;
  p.brdf_candidates = brdf;
  p.combine = combine;
  p.candidates = 8;
  p.radius = 8.0f;
  return p;
}

// Per 4x4 block and channel (192 Welch tests, 22 degrees of freedom) ReSTIR DI's direct layer
// against pt's with max_bounces 0: |t| > 6.5 has a probability below 1e-5 over the image under
// the null hypothesis. Neighbouring pixels share samples, so the blocks' spread over the seeds,
// not the pixels', measures the error.
void expect_converges(const Scene& scene, bool diffuse_only, const Variant* variants, size_t count) {
  RenderOptions pt_options = options("pt", "power", diffuse_only, 16, 0);
  test::SeedBlockMeans pt = direct_blocks(scene, pt_options, {{"max_bounces", 0}});
  for (size_t i = 0; i < count; ++i) {
    const Variant& v = variants[i];
    RenderOptions o = options("pt", v.sampler, diffuse_only, 16, 0);
    o.direct_sampler = "restir";
    o.restir = v.restir;
    test::SeedBlockMeans r = direct_blocks(scene, o, {{"max_bounces", 0}});
    test::BlockTTest t = test::block_t_test(r, pt, 6.5);
    std::printf("restir %s (%s): largest |t| %.2f over %d blocks; image mean %.5f vs %.5f (pt); summed variance "
                "of the block means %.3e vs %.3e\n",
                v.name, v.sampler, t.largest, r.size(), r.image_mean(), pt.image_mean(), r.summed_variance(),
                pt.summed_variance());
    EXPECT_EQ(t.failures, 0) << v.name << " " << v.sampler;
  }
}

TEST(RestirDi, UnbiasedConvergesToThePathTracerAmongManyLights) {
  // 800 emissive triangles, 5 point and 5 spot lights and a sun over occluders.
  Scene scene = test::many_lights(31, 800, 5, 5, true);
  const Variant variants[] = {
      {"initial only", "power", restir_params(0, 0, "unbiased")},
      {"two spatial passes", "power", restir_params(2, 1, "unbiased")},
      {"one spatial pass", "tree", restir_params(1, 1, "unbiased")},
      {"one spatial pass", "uniform", restir_params(1, 0, "unbiased")},
  };
  expect_converges(scene, true, variants, std::size(variants));
}

// The fourth frame's direct light over sequences of independent seeds (frames at `spp`), each
// 4x4 block's mean and its spread over the seeds.
test::SeedBlockMeans fourth_frames(const Scene& scene, const std::vector<KeyFramePath>& paths, bool restir, int spp,
                                   int seeds) {
  test::SeedBlockMeans blocks(kSize, kSize, kBlock);
  for (int seed = 0; seed < seeds; ++seed) {
    RenderOptions o = options("pt", "power", true, spp, uint32_t(900 + seed));
    if (restir) {
      o.direct_sampler = "restir";
      o.restir = restir_params(1, 1, "unbiased");
      o.restir.temporal = true;
    }
    o.frames = 4;
    Image last;
    Scene posed = scene;
    render_sequence(posed, paths, o, {{"max_bounces", 0}}, true, [&](SequenceFrame& f) { last = f.result.frame.direct; });
    blocks.add(last);
  }
  return blocks;
}

// Temporal reuse across frames, of a static view, of a turning camera (whose history is found by
// reprojection) and of lights that move (whose history is evaluated where they are now): the fourth
// frame (1 spp each, 36 seeds) converges to pt's direct light of the same frame (16 spp, 12 seeds).
TEST(RestirDi, TemporalReuseAcrossFramesConvergesToThePathTracer) {
  Scene scene = test::many_lights(31, 800, 5, 5, true);
  std::vector<KeyFramePath> turning = parse_key_frame_paths(
      nlohmann::json::parse(R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 30}]}])"), scene, "test");
  // 40 emissive triangles and four point lights that outshine them, each moving 0.4 m a frame.
  Scene few = test::many_lights(32, 40, 4, 0, false);
  nlohmann::json moving = nlohmann::json::array();
  for (int light = 0; light < 4; ++light)
    moving.push_back({{"light", std::to_string(light)},
                      {"keys", {{{"time", 0}, {"translate", {0, 0, 0}}}, {{"time", 0.1}, {"translate", {1.2, 0, 0.4}}}}}});
  const std::vector<KeyFramePath> lights_moving = parse_key_frame_paths(moving, few, "test");
  struct Case {
    const char* name;
    const Scene& scene;
    std::vector<KeyFramePath> paths;
  };
  for (const Case& c : {Case{"static view", scene, {}}, Case{"turning camera", scene, turning},
                        Case{"moving lights", few, lights_moving}}) {
    test::SeedBlockMeans pt = fourth_frames(c.scene, c.paths, false, 16, kSeeds);
    test::SeedBlockMeans r = fourth_frames(c.scene, c.paths, true, 1, 3 * kSeeds);
    test::BlockTTest t = test::block_t_test(r, pt, 6.5);
    std::printf("restir, frame 4 of a %s: largest |t| %.2f over %d blocks; image mean %.5f vs %.5f (pt)\n", c.name,
                t.largest, r.size(), r.image_mean(), pt.image_mean());
    EXPECT_EQ(t.failures, 0) << c.name;
  }
}

// The mean squared error of the direct light of the last frame of a sequence (1 spp a frame)
// against pt at 256 spp, over the pixels no emitter touches (`mask` zero: the emitters alone).
double sequence_mse(const Scene& scene, const std::vector<KeyFramePath>& paths, bool temporal, int frames,
                    const Image& reference, const Image& mask) {
  RenderOptions o = options("pt", "power", true, 1, 3);
  o.direct_sampler = "restir";
  o.restir = restir_params(1, 1, "unbiased");
  o.restir.temporal = temporal;
  o.frames = frames;
  Image last;
  Scene posed = scene;
  render_sequence(posed, paths, o, {{"max_bounces", 0}}, true, [&](SequenceFrame& f) { last = f.result.frame.direct; });
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < last.data.size(); ++i) {
    if (mask.data[i] != 0.0f) continue;
    sum += double(last.data[i] - reference.data[i]) * (last.data[i] - reference.data[i]);
    ++count;
  }
  return sum / count;
}

// Across 8 frames of a static view, temporal reuse lowers the last frame's error against the same
// sequence without it (M grows to its cap). The gain is modest here: 33 candidates from the power
// sampler already come close to the unshadowed target, and temporal reuse cannot learn the
// occluders' shadows beyond what visibility reuse does (docs/restir.md). Measured at these seeds:
// x0.62 with the default cap (1), x0.50 with the paper's 20.
TEST(RestirDi, TemporalReuseAcrossFramesLowersTheError) {
  Scene scene = test::many_lights(31, 800, 5, 5, true);
  RenderOptions ref_options = options("pt", "power", true, 256, 77);
  const Image reference = render_frame(scene, ref_options, {{"max_bounces", 0}}).frame.direct;
  const Image mask = render_frame(emitters_only(scene), ref_options, {{"max_bounces", 0}}).frame.color;
  double with = sequence_mse(scene, {}, true, 8, reference, mask);
  double without = sequence_mse(scene, {}, false, 8, reference, mask);
  std::printf("direct-light MSE of frame 8 of a static view: %.4e with temporal reuse, %.4e without (x%.2f)\n", with,
              without, with / without);
  EXPECT_LT(with, 0.85 * without);
}

// Glossy materials: the BRDF candidate and the light samples are combined by the balance
// heuristic, so light reaching glossy lobes is neither lost nor counted twice. (Without the BRDF
// candidate the estimate stays unbiased, but on the box's near-mirror surfaces its rare large
// values make 12 seeds read 3% low: docs/restir.md.)
TEST(RestirDi, UnbiasedConvergesToThePathTracerOnGlossySurfaces) {
  Scene scene = load_default_scene();
  const Variant variants[] = {
      {"with a BRDF candidate", "power", restir_params(1, 1, "unbiased")},
      {"with a BRDF candidate", "tree", restir_params(2, 1, "unbiased")},
  };
  expect_converges(scene, false, variants, std::size(variants));
}

// The biased combination drops the neighbours' shadow rays: at shadow edges the pixel's own
// sample keeps less weight than it should. Measured on the many-light scene (its occluders make
// shadow edges everywhere), the same seeds for both combinations, so that the emission the camera
// sees, the same in both, cancels from their difference.
TEST(RestirDi, BiasedCombinationDarkensShadowEdgesSlightly) {
  Scene scene = test::many_lights(31, 800, 5, 5, true);
  RenderOptions pt_options = options("pt", "power", true, 16, 0);
  test::SeedBlockMeans pt = direct_blocks(scene, pt_options, {{"max_bounces", 0}});
  double means[2];
  const char* combines[2] = {"unbiased", "biased"};
  for (int i = 0; i < 2; ++i) {
    RenderOptions o = options("pt", "power", true, 16, 0);
    o.direct_sampler = "restir";
    o.restir = restir_params(2, 0, combines[i]);
    o.restir.radius = 30.0f;
    means[i] = direct_blocks(scene, o, {{"max_bounces", 0}}).image_mean();
  }
  std::printf("image mean / pt's: unbiased %.4f, biased %.4f; biased / unbiased %.4f\n", means[0] / pt.image_mean(),
              means[1] / pt.image_mean(), means[1] / means[0]);
  EXPECT_NEAR(means[0] / pt.image_mean(), 1.0, 0.01);
  EXPECT_LT(means[1], means[0]);
  EXPECT_GT(means[1] / means[0], 0.95);
}

// Every method's direct light comes from the ReSTIR pass alone: with it, pt's direct layer holds
// the emission the camera sees plus ReSTIR's estimate, and its indirect layer is unchanged.
TEST(RestirDi, MethodsGatherNoDirectLightOfTheirOwn) {
  Scene scene = load_default_scene();
  RenderOptions o = options("pt", "power", true, 1, 9);
  o.direct_sampler = "restir";
  o.restir.candidates = 1;
  RenderResult with = render_frame(scene, o, {{"max_bounces", 2}});
  RenderOptions plain = o;
  plain.direct_sampler = "nee";
  RenderResult without = render_frame(scene, plain, {{"max_bounces", 2}});
  // The paths after the first hit draw the same numbers either way.
  EXPECT_EQ(with.frame.indirect.data, without.frame.indirect.data);
  // Camera, ReSTIR's camera, its one BRDF ray and its shadow rays: more rays than the paths alone.
  EXPECT_GT(with.frame.counters.primary_rays, without.frame.counters.primary_rays);
}

TEST(RestirDi, BadParametersAreErrorsThatNameThem) {
  Scene scene = load_default_scene();
  auto message = [&](auto edit) {
    RenderOptions o = options("pt", "power", true, 1, 0);
    o.direct_sampler = "restir";
    edit(o);
    try {
      render_frame(scene, o, {});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([](RenderOptions& o) { o.direct_sampler = "ris"; }).find("direct_sampler"), std::string::npos);
  EXPECT_NE(message([](RenderOptions& o) { o.restir.candidates = 0; }).find("restir_candidates"), std::string::npos);
  EXPECT_NE(message([](RenderOptions& o) { o.restir.neighbours = 17; }).find("restir_neighbours"), std::string::npos);
  EXPECT_NE(message([](RenderOptions& o) { o.restir.radius = 0.5f; }).find("restir_radius"), std::string::npos);
  EXPECT_NE(message([](RenderOptions& o) { o.restir.combine = "pairwise"; }).find("restir_combine"),
            std::string::npos);
  EXPECT_NE(message([](RenderOptions& o) { o.restir.brdf_candidates = 2; }).find("restir_brdf_candidates"),
            std::string::npos);
  EXPECT_EQ(message([](RenderOptions&) {}), "no error");
}

}  // namespace
}  // namespace sst
