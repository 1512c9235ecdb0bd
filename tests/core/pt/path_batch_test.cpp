// Paths in batches (core/pt/path_batch.h) against paths traced one at a time: the same image bits
// and the same ray counts for every batch size and every way of handing Embree a batch of rays.
#include "core/pt/path_batch.h"

#include <gtest/gtest.h>

#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "tests/analytic_scenes.h"
#include "tests/core/scene/gltf_feature_scenes.h"
#include "tests/test_util.h"

namespace sst {
namespace {

RenderResult render(const Scene& scene, RenderOptions options, const nlohmann::json& params, int batch,
                    const std::string& rays) {
  options.path_batch = batch;
  options.batch_rays = rays;
  return render_frame(scene, options, params);
}

// Every layer and counter of `got` equals `want`'s exactly.
void expect_same_bits(const RenderResult& want, const RenderResult& got) {
  EXPECT_EQ(want.frame.color.data, got.frame.color.data);
  EXPECT_EQ(want.frame.direct.data, got.frame.direct.data);
  EXPECT_EQ(want.frame.indirect.data, got.frame.indirect.data);
  EXPECT_EQ(want.frame.albedo.data, got.frame.albedo.data);
  EXPECT_EQ(want.frame.normal.data, got.frame.normal.data);
  EXPECT_EQ(want.frame.depth.data, got.frame.depth.data);
  EXPECT_EQ(want.frame.counters.primary_rays, got.frame.counters.primary_rays);
  EXPECT_EQ(want.frame.counters.shadow_rays, got.frame.counters.shadow_rays);
  EXPECT_EQ(want.frame.counters.bounce_rays, got.frame.counters.bounce_rays);
  EXPECT_EQ(want.frame.counters.samples, got.frame.counters.samples);
}

// A batch size that splits a tile's paths unevenly (7), one smaller than a tile's pixels, one
// larger than a tile's paths, with every ray API.
void expect_every_batch_matches(const Scene& scene, const RenderOptions& options, const nlohmann::json& params) {
  const RenderResult alone = render(scene, options, params, 0, "stream");
  ASSERT_GT(alone.frame.counters.bounce_rays, 0u);
  for (int batch : {1, 7, 100, 5000})
    for (const char* rays : {"single", "stream", "packet8", "packet16"}) {
      SCOPED_TRACE(std::string("batch ") + std::to_string(batch) + " " + rays);
      expect_same_bits(alone, render(scene, options, params, batch, rays));
    }
}

RenderOptions small(const std::string& method) {
  RenderOptions options;
  options.method = method;
  options.width = 36;
  options.height = 20;
  options.spp = 3;
  options.seed = 5;
  return options;
}

TEST(PathBatch, PathTracerImageIsTheSameBitsForEveryBatchAndRayApi) {
  expect_every_batch_matches(load_default_scene(), small("pt"), {{"max_bounces", 6}, {"rr_min_bounces", 1}});
}

TEST(PathBatch, FlatBvhImageIsTheSameBitsForEveryBatch) {
  RenderOptions options = small("pt");
  options.accel = "flat";
  expect_every_batch_matches(load_default_scene(), options, {{"max_bounces", 3}});
}

// Embree's filter functions do the alpha test for packets and streams as for single rays.
TEST(PathBatch, AlphaMaskedImageIsTheSameBitsForEveryBatch) {
  const test::fs::path dir = test::temp_dir();
  for (const test::FeatureScene& f : test::feature_scenes(dir)) {
    if (f.name != "mask_white") continue;
    RenderOptions options = small("pt");
    options.diffuse_only = true;
    expect_every_batch_matches(load_gltf(f.path.string()), options, {{"max_bounces", 2}});
    return;
  }
  FAIL() << "no mask_white feature scene";
}

// The many-light methods' direct pass is the batched path; rtslc adds its own direct estimate with
// the sampler where the path left it.
TEST(PathBatch, ManyLightMethodsAreTheSameBitsForEveryBatch) {
  const Scene scene = load_default_scene();
  for (const char* method : {"sst", "rtslc"}) {
    SCOPED_TRACE(method);
    const RenderOptions options = small(method);
    const nlohmann::json params = {{"vpls", 500}};
    const RenderResult alone = render(scene, options, params, 0, "stream");
    for (int batch : {7, 1024}) expect_same_bits(alone, render(scene, options, params, batch, "stream"));
  }
}

TEST(PathBatch, RejectsImpossibleSettings) {
  RenderOptions options = small("pt");
  const Scene scene = test::emissive_box(0.5f, 1.0f, 2.0f);
  EXPECT_THROW(render(scene, options, {}, -1, "stream"), Error);
  EXPECT_THROW(render(scene, options, {}, 64, "packet4"), Error);
}

}  // namespace
}  // namespace sst
