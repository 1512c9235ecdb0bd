#include "core/eval/experiment_config.h"

#include <gtest/gtest.h>

#include "core/util/error.h"

namespace sst {
namespace {

using nlohmann::json;

std::string error_of(const json& config) {
  try {
    expand_runs(parse_experiment_config(config, "cfg.json"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ExperimentConfig, UnknownKeysAreErrorsNamingTheNearestKey) {
  EXPECT_EQ(error_of({{"sedds", 2}}), "cfg.json: unknown key 'sedds' (did you mean 'seeds'?)");
  EXPECT_EQ(error_of({{"base", {{"vlps", 10}}}}), "cfg.json: base: unknown parameter 'vlps' (did you mean 'vpls'?)");
  EXPECT_EQ(error_of({{"axes", {{"blok_size", {1, 2}}}}}),
            "cfg.json: axes: unknown parameter 'blok_size' (did you mean 'block_size'?)");
  EXPECT_NE(error_of({{"variants", {{{"name", "a"}, {"parms", json::object()}}}}}).find("unknown key 'parms'"),
            std::string::npos);
  EXPECT_NE(error_of({{"reference", {{"kind", "photon"}}}}).find("unknown kind 'photon'"), std::string::npos);
  EXPECT_NE(error_of({{"reference", {{"spp", 8}, {"vpls", 3}}}}).find("'vpls' is not a parameter of its method 'pt'"),
            std::string::npos);
  EXPECT_NE(error_of({{"method", "pt"}, {"reference", {{"kind", "vpl"}}}}).find("needs a VPL method"), std::string::npos);
}

TEST(ExperimentConfig, ConflictsAndImpossibleValuesFailBeforeRendering) {
  EXPECT_NE(error_of({{"spp", 4}, {"axes", {{"spp", {1, 2}}}}}).find("both a sweep axis and a base parameter"),
            std::string::npos);
  EXPECT_NE(error_of({{"axes", {{"spp", {1, 2}}}}, {"variants", {{{"name", "a"}, {"params", {{"spp", 3}}}}}}})
                .find("also a sweep axis"),
            std::string::npos);
  EXPECT_NE(error_of({{"seeds", 0}}).find("seeds"), std::string::npos);
  EXPECT_NE(error_of({{"axes", {{"spp", json::array()}}}}).find("non-empty list"), std::string::npos);
  EXPECT_EQ(error_of({{"method", "slc"}, {"axes", {{"cut_size", {8, 64}}}}}), "");  // not an slc parameter: dropped
  EXPECT_NE(error_of({{"method", "rtslc"}, {"axes", {{"cut_size", {8, 64}}}}}).find("run 1"), std::string::npos);
  EXPECT_NE(error_of({{"axes", {{"method", {"pt", "slcc"}}}}}).find("did you mean 'slc'"), std::string::npos);
  EXPECT_NE(error_of({{"time_budget_ms", -1}}).find("time_budget_ms"), std::string::npos);
  EXPECT_NE(error_of({{"metrics_layer", "albedo"}}).find("metrics_layer"), std::string::npos);
  EXPECT_EQ(error_of({{"metrics_layer", "direct"}}), "");
}

TEST(ExperimentConfig, ExpandsTheProductOfAxesTimesVariantsTimesSeeds) {
  json j = {{"scenes", {"", "x"}},
            {"width", 32},
            {"axes", {{"vpls", {100, 1000}}, {"method", {"slc", "sst", "pt"}}}},
            {"variants", {{{"name", "fast"}, {"params", {{"spp", 1}}}}, {{"name", "slow"}, {"params", {{"spp", 4}}}}}},
            {"seeds", 3}};
  std::vector<RunSpec> runs = expand_runs(parse_experiment_config(j, "cfg"));
  ASSERT_EQ(runs.size(), 2u * 2 * 3 * 2 * 3);
  // Axes in name order, the last fastest: method outer, vpls inner; then variants, then seeds.
  EXPECT_EQ(runs[0].axes, json({{"method", "slc"}, {"vpls", 100}}));
  EXPECT_EQ(runs[6].axes, json({{"method", "slc"}, {"vpls", 1000}}));
  EXPECT_EQ(runs[12].axes["method"], "sst");
  EXPECT_EQ(runs[3].variant, "slow");
  EXPECT_EQ(runs[3].options["spp"], 4);
  EXPECT_EQ(runs[1].seed, 1u);
  EXPECT_EQ(runs[1].group, runs[0].group);  // seeds share a group
  EXPECT_NE(runs[3].group, runs[0].group);
  EXPECT_EQ(runs[0].label, "fast/slc");
  EXPECT_EQ(runs[36].scene, "x");
  for (size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].index, int(i));
  EXPECT_EQ(runs[3].id, "0003-slow_slc");
}

TEST(ExperimentConfig, ParametersOfOtherMethodsAreDroppedFromARun) {
  json j = {{"vpls", 5000}, {"max_bounces", 2}, {"axes", {{"method", {"pt", "slc"}}}}};
  std::vector<RunSpec> runs = expand_runs(parse_experiment_config(j, "cfg"));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].method_params, json({{"max_bounces", 2}}));
  EXPECT_EQ(runs[1].method_params, json({{"vpls", 5000}}));
  EXPECT_EQ(runs[0].options["method"], "pt");
  EXPECT_EQ(runs[1].label, "slc");
}

TEST(ExperimentConfig, SpecHashChangesWithAnythingThatChangesTheImage) {
  auto hash = [](json j) { return expand_runs(parse_experiment_config(j, "cfg")).front().spec_hash; };
  json base = {{"method", "slc"}, {"vpls", 1000}};
  EXPECT_EQ(hash(base), hash(base));
  EXPECT_NE(hash(base), hash({{"method", "slc"}, {"vpls", 1001}}));
  EXPECT_NE(hash(base), hash({{"method", "slc"}, {"vpls", 1000}, {"seed", 1}}));
  EXPECT_NE(hash(base), hash({{"method", "slc"}, {"vpls", 1000}, {"scene", "other"}}));
  EXPECT_NE(hash(base), hash({{"method", "slc"}, {"vpls", 1000}, {"time_budget_ms", 5}}));
}

}  // namespace
}  // namespace sst
