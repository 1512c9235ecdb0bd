// Temporal accumulation: running means under a static view, history rejected where the surface
// changed, bilinear reprojection of a shifted history.
#include <gtest/gtest.h>

#include "core/math/vector_math.h"
#include "core/temporal/temporal_reuse.h"
#include "core/image/image.h"
#include "core/util/error.h"

namespace sst {
namespace {

TemporalInput input(vec3 direct, vec3 indirect, float depth, vec3 normal, vec2 motion) {
  TemporalInput t{};
  t.direct = direct;
  t.indirect = indirect;
  t.depth = depth;
  t.previous_depth = depth;
  t.normal = normal;
  t.motion = motion;
  t.albedo = vec3(1.0f);
  t.luminance = vec2(luminance(direct), luminance(indirect));
  return t;
}

TemporalPush push(int w, int h, int cap) {
  TemporalParams p;
  p.history_cap = cap;
  return temporal_push(p, w, h);
}

TEST(TemporalReuse, StaticViewKeepsTheRunningMeanUpToTheCapThenAnExponentialOne) {
  const int w = 3, h = 2;
  std::vector<TemporalTexel> history;
  std::vector<float> values{1.0f, 3.0f, 2.0f, 6.0f, 0.0f};
  double sum = 0.0;
  for (size_t f = 0; f < values.size(); ++f) {
    std::vector<TemporalInput> in(w * h, input(vec3(values[f]), vec3(2.0f * values[f]), 1.0f, vec3(0, 0, 1), vec2(0.0f)));
    history = temporal_accumulate(in, history, push(w, h, 4));
    sum += values[f];
    if (f < 4) {
      EXPECT_FLOAT_EQ(history[4].direct.x, float(sum / double(f + 1)));
      EXPECT_FLOAT_EQ(history[4].indirect.y, float(2.0 * sum / double(f + 1)));
      EXPECT_FLOAT_EQ(history[4].frames, float(f + 1));
    }
  }
  // Frame 5 at the cap of 4: alpha = 1/4 on the mean of the first four (3.0).
  EXPECT_FLOAT_EQ(history[0].direct.x, 3.0f + (0.0f - 3.0f) * 0.25f);
  EXPECT_FLOAT_EQ(history[0].frames, 4.0f);
  // Moments: luminance of a grey value is the value.
  EXPECT_NEAR(history[0].moments.x, history[0].direct.x, 1e-5f);
}

// The history averages radiance and albedo alike, so that remodulating its illumination (their
// ratio) gives back the plain mean of the frames' radiance, however the albedo of the samples varied.
TEST(TemporalReuse, RadianceAndAlbedoAverageAlikeSoRemodulationIsExact) {
  const int w = 1, h = 1;
  std::vector<TemporalTexel> history;
  const float albedo[3] = {0.1f, 0.9f, 0.5f}, irradiance[3] = {4.0f, 1.0f, 2.0f};
  double radiance_sum = 0.0, albedo_sum = 0.0;
  for (int f = 0; f < 3; ++f) {
    vec3 radiance(albedo[f] * irradiance[f]);
    TemporalInput in = input(vec3(0.0f), radiance, 1.0f, vec3(0, 0, 1), vec2(0.0f));
    in.albedo = vec3(albedo[f]);
    history = temporal_accumulate({in}, history, push(w, h, 8));
    radiance_sum += radiance.x;
    albedo_sum += albedo[f];
  }
  TemporalImages images = temporal_images(history, w, h);
  EXPECT_FLOAT_EQ(images.albedo.at(0, 0, 0), float(albedo_sum / 3.0));
  EXPECT_NEAR(images.indirect.at(0, 0, 0) * images.albedo.at(0, 0, 0), radiance_sum / 3.0, 1e-6);
}

TEST(TemporalReuse, ADisocclusionOrANewNormalRestartsTheHistory) {
  const int w = 2, h = 1;
  std::vector<TemporalInput> first(w * h, input(vec3(1.0f), vec3(1.0f), 5.0f, vec3(0, 0, 1), vec2(0.0f)));
  std::vector<TemporalTexel> history = temporal_accumulate(first, {}, push(w, h, 8));
  std::vector<TemporalInput> second = first;
  for (auto& t : second) t.direct = t.indirect = vec3(3.0f);
  second[0].previous_depth = 4.0f;         // 20% nearer than the history saw: another surface
  second[1].normal = vec3(1.0f, 0.0f, 0.0f);  // the same depth, but facing elsewhere
  std::vector<TemporalTexel> next = temporal_accumulate(second, history, push(w, h, 8));
  for (const TemporalTexel& t : next) {
    EXPECT_FLOAT_EQ(t.frames, 1.0f);
    EXPECT_FLOAT_EQ(t.direct.x, 3.0f);
  }
  // Within the tolerances, the history is kept.
  second[0].previous_depth = 5.2f;
  second[1].normal = glm::normalize(vec3(0.1f, 0.0f, 1.0f));
  next = temporal_accumulate(second, history, push(w, h, 8));
  for (const TemporalTexel& t : next) {
    EXPECT_FLOAT_EQ(t.frames, 2.0f);
    EXPECT_FLOAT_EQ(t.direct.x, 2.0f);
  }
}

// On a surface whose normal turns fast from pixel to pixel, a history tap a pixel away may face
// as differently as the neighbours do: the normal bound widens by that change (measured by
// temporal_inputs from the 4-neighbours), and the history is kept.
TEST(TemporalReuse, TheNormalBoundWidensWhereTheNormalTurnsAcrossPixels) {
  const int w = 3, h = 1;
  auto images = [&](vec3 middle) {
    Image depth(w, h, 1), normal(w, h, 3), motion(w, h, 2), black(w, h, 3), albedo(w, h, 3);
    const vec3 normals[3] = {glm::normalize(vec3(-1.0f, 0.0f, 1.0f)), middle, glm::normalize(vec3(1.0f, 0.0f, 1.0f))};
    for (int x = 0; x < w; ++x) {
      depth.at(x, 0, 0) = 2.0f;
      normal.set_rgb(x, 0, normals[x]);
      albedo.set_rgb(x, 0, vec3(0.5f));
    }
    return temporal_inputs(black, black, albedo, depth, normal, motion, depth);
  };
  std::vector<TemporalInput> first = images(vec3(0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(first[1].normal_change, glm::length(first[0].normal - first[1].normal), 1e-6f);
  std::vector<TemporalTexel> history = temporal_accumulate(first, {}, push(w, h, 8));
  // The middle pixel now faces 30 degrees away (cosine 0.87 < 0.9): kept, its neighbours turn 45.
  std::vector<TemporalInput> second = images(glm::normalize(vec3(0.5f, 0.0f, 0.866f)));
  EXPECT_FLOAT_EQ(temporal_accumulate(second, history, push(w, h, 8))[1].frames, 2.0f);
  // With flat neighbours the same turn is another surface.
  for (TemporalInput& t : second) t.normal_change = 0.0f;
  EXPECT_FLOAT_EQ(temporal_accumulate(second, history, push(w, h, 8))[1].frames, 1.0f);
}

TEST(TemporalReuse, HistoryIsReadBilinearlyAtTheMotionVector) {
  const int w = 4, h = 1;
  std::vector<TemporalInput> first(w * h);
  for (int x = 0; x < w; ++x) first[x] = input(vec3(float(x)), vec3(0.0f), 1.0f, vec3(0, 0, 1), vec2(0.0f));
  std::vector<TemporalTexel> history = temporal_accumulate(first, {}, push(w, h, 2));
  // The pixel was a quarter pixel to the right of pixel 1 in the previous frame: history 1.25.
  std::vector<TemporalInput> second(w * h, input(vec3(0.0f), vec3(0.0f), 1.0f, vec3(0, 0, 1), vec2(0.25f, 0.0f)));
  std::vector<TemporalTexel> next = temporal_accumulate(second, history, push(w, h, 2));
  EXPECT_FLOAT_EQ(next[1].direct.x, 0.5f * 1.25f);
  // The last pixel's right tap is outside the image: its left tap alone carries the history.
  EXPECT_FLOAT_EQ(next[3].direct.x, 0.5f * 3.0f);
  // A miss (depth 0) reads only the history of misses: none here.
  second[2].depth = 0.0f;
  next = temporal_accumulate(second, history, push(w, h, 2));
  EXPECT_FLOAT_EQ(next[2].frames, 1.0f);
  // Where the previous frame missed too, it continues that history.
  std::vector<TemporalInput> misses(w * h, input(vec3(2.0f), vec3(0.0f), 0.0f, vec3(0.0f), vec2(0.0f)));
  history = temporal_accumulate(misses, {}, push(w, h, 4));
  for (auto& t : misses) t.direct = vec3(4.0f);
  next = temporal_accumulate(misses, history, push(w, h, 4));
  EXPECT_FLOAT_EQ(next[1].frames, 2.0f);
  EXPECT_FLOAT_EQ(next[1].direct.x, 3.0f);
}

TEST(TemporalReuse, ParametersAreValidated) {
  TemporalParams p;
  p.history_cap = 0;
  EXPECT_THROW(validate(p), Error);
  p = TemporalParams{};
  p.normal_cos = 2.0f;
  EXPECT_THROW(validate(p), Error);
}

}  // namespace
}  // namespace sst
