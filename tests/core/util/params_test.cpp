#include "core/util/params.h"

#include <gtest/gtest.h>

#include "core/render/render_options.h"

namespace sst {
namespace {

TEST(Params, RoundTripsEveryField) {
  RenderOptions o;
  o.width = 123;
  o.spp = 7;
  o.diffuse_only = true;
  o.camera = "main";
  o.exposure = 1.5f;
  nlohmann::json j = params_to_json(o);
  RenderOptions back;
  params_from_json(back, j, "test");
  EXPECT_EQ(params_to_json(back), j);
  EXPECT_EQ(j.size(), param_names<RenderOptions>().size());
}

TEST(Params, UnknownKeyNamesTheNearestValidOne) {
  RenderOptions o;
  try {
    params_from_json(o, {{"sp", 4}}, "configs/x.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "configs/x.json: unknown parameter 'sp' (did you mean 'spp'?)");
  }
}

TEST(Params, WrongTypesAreErrors) {
  RenderOptions o;
  EXPECT_THROW(params_from_json(o, {{"spp", "many"}}, "x"), Error);
  EXPECT_THROW(params_from_json(o, {{"spp", 1.5}}, "x"), Error);
  EXPECT_THROW(params_from_json(o, {{"diffuse_only", 1}}, "x"), Error);
  EXPECT_THROW(params_from_json(o, {{"seed", -1}}, "x"), Error);
  EXPECT_THROW(params_from_json(o, nlohmann::json::array(), "x"), Error);
}

TEST(Params, NearestName) {
  EXPECT_EQ(nearest_name("max_bounce", {"max_bounces", "spp", "seed"}), "max_bounces");
  EXPECT_EQ(to_flag("v_min"), "v-min");
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {
TEST(Params, FloatsAreWrittenAsTheirShortestDecimal) {
  EXPECT_EQ(shortest_decimal(0.01f), 0.01);
  EXPECT_EQ(float(shortest_decimal(0.1f + 0.2f)), 0.1f + 0.2f);
  RenderOptions o;
  o.exposure = 0.3f;
  EXPECT_EQ(params_to_json(o)["exposure"].dump(), "0.3");
}
}  // namespace
}  // namespace sst
