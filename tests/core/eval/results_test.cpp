#include "core/eval/results.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/image/image.h"
#include "tests/test_util.h"

namespace sst {
namespace {

using nlohmann::json;

json run_record(int index, const std::string& group, double time_ms, double rmse, double ssim, uint32_t seed = 0) {
  std::string id = "000" + std::to_string(index) + "-x";
  return {{"id", id},
          {"index", index},
          {"group", group},
          {"label", group},
          {"scene", "s"},
          {"method", "slc"},
          {"variant", ""},
          {"axes", json::object()},
          {"seed", seed},
          {"spp", 1},
          {"params", {{"diffuse_only", false}}},
          {"reference", "ref"},
          {"reference_description", {{"kind", "path"}}},
          {"time_budget_ms", nullptr},
          {"time_ms", {{"median", time_ms}, {"min", time_ms}, {"max", time_ms}}},
          {"stages", json::object()},
          {"metrics", {{"rmse", rmse}, {"ssim", ssim}, {"rel_mse", 0.0}, {"psnr", 0.0}}},
          {"images", {{"exr", "runs/" + id + "/image.exr"}}}};
}

TEST(Results, ParetoFrontGainAndEfficiency) {
  std::vector<json> runs = {run_record(0, "cheap", 1.0, 0.5, 0.5), run_record(1, "good", 4.0, 0.1, 0.9),
                            run_record(2, "dominated", 5.0, 0.2, 0.8), run_record(3, "mid", 2.0, 0.3, 0.6)};
  json r = assemble_results(ExperimentConfig{}, runs, test::temp_dir().string());
  std::map<std::string, bool> pareto;
  for (const json& g : r["groups"]) pareto[g["group"]] = g["pareto"];
  EXPECT_TRUE(pareto["cheap"]);
  EXPECT_TRUE(pareto["good"]);
  EXPECT_TRUE(pareto["mid"]);
  EXPECT_FALSE(pareto["dominated"]);
  // Gain over the lowest-SSIM run (cheap): 100 (0.9 - 0.5) / 0.5 / (4 - 1) %/ms.
  EXPECT_NEAR(r["runs"][1]["ssim_gain_pct_per_ms"].get<double>(), 100.0 * 0.4 / 0.5 / 3.0, 1e-9);
  EXPECT_TRUE(r["runs"][0]["ssim_gain_pct_per_ms"].is_null());
  EXPECT_EQ(r["runs"][1]["gain_base"], "0000-x");
  EXPECT_NEAR(r["runs"][1]["efficiency"].get<double>(), 1.0 / (0.01 * 0.004), 1e-6);
  EXPECT_TRUE(r["groups"][0]["bias2"].is_null());  // one seed: no bias/variance split
}

TEST(Results, BiasAndVarianceOverSeedsMatchTheDirectComputation) {
  auto dir = test::temp_dir();
  // Reference 1 everywhere; seeds give 1 + b + e_s with e = (+d, -d, +2d, -2d) per pixel.
  const double b = 0.25, d = 0.1;
  const double e[4] = {d, -d, 2 * d, -2 * d};
  write_image((dir / "references/ref.exr").string(), [] {
    Image img(4, 2);
    std::fill(img.data.begin(), img.data.end(), 1.0f);
    return img;
  }());
  std::vector<json> runs;
  for (int s = 0; s < 4; ++s) {
    Image img(4, 2);
    std::fill(img.data.begin(), img.data.end(), float(1.0 + b + e[s]));
    json rec = run_record(s, "g", 1.0, 0.1, 0.9, uint32_t(s));
    write_image((dir / rec["images"]["exr"].get<std::string>()).string(), img);
    runs.push_back(rec);
  }
  json r = assemble_results(ExperimentConfig{}, runs, dir.string());
  const json& g = r["groups"][0];
  double variance = (d * d * 2 + 4 * d * d * 2) / 3.0;  // unbiased sample variance of e (mean 0)
  EXPECT_NEAR(g["variance"].get<double>(), variance, 1e-6);
  EXPECT_NEAR(g["bias2"].get<double>(), b * b - variance / 4.0, 1e-6);
  EXPECT_EQ(g["seeds"], 4);
  EXPECT_NEAR(g["rmse_std"].get<double>(), 0.0, 1e-12);
}

TEST(Results, RobustSeedStatisticsIgnoreOneOutlier) {
  std::vector<json> runs;
  const double rmse[5] = {0.10, 0.11, 0.09, 0.10, 5.0};  // the last seed met a firefly
  for (int s = 0; s < 5; ++s) runs.push_back(run_record(s, "g", 1.0, rmse[s], 0.9, uint32_t(s)));
  json g = assemble_results(ExperimentConfig{}, runs, test::temp_dir().string())["groups"][0];
  EXPECT_NEAR(g["rmse_median"].get<double>(), 0.10, 1e-12);
  EXPECT_NEAR(g["rmse_robust_std"].get<double>(), 1.4826 * 0.01, 1e-9);
  EXPECT_NEAR(g["rmse_mean"].get<double>(), 1.08, 1e-12);
  EXPECT_GT(g["rmse_std"].get<double>(), 2.0);
}

TEST(Results, CsvHasOneRowPerRunAndAxisColumns) {
  std::vector<json> runs = {run_record(0, "a", 1.0, 0.5, 0.5), run_record(1, "b", 2.0, 0.25, 0.7)};
  runs[0]["axes"] = {{"vpls", 10}, {"method", "slc"}};
  runs[1]["axes"] = {{"vpls", 20}, {"method", "slc"}};
  std::string csv = results_csv(assemble_results(ExperimentConfig{}, runs, test::temp_dir().string()));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_EQ(csv.rfind("id,index,scene,label,method,variant,seed,vpls,spp,", 0), 0u) << csv;
  EXPECT_NE(csv.find("0001-x,1,s,b,slc,,0,20,1,"), std::string::npos) << csv;
}

}  // namespace
}  // namespace sst
