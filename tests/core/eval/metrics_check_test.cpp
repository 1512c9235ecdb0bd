#include "core/eval/metrics_check.h"

#include <gtest/gtest.h>

#include "core/util/json_io.h"

namespace sst {
namespace {

using nlohmann::json;

json results(double rmse, double rmse_robust_std, double ssim, int seeds = 4, size_t nonfinite = 0) {
  return {{"groups",
           {{{"group", "slc"}, {"seeds", seeds}, {"rmse_median", rmse}, {"rmse_robust_std", rmse_robust_std},
             {"ssim_median", ssim}, {"ssim_robust_std", 0.001}, {"time_ms_median", 10.0}}}},
          {"runs", {{{"group", "slc"}, {"metrics", {{"nonfinite_test", nonfinite}}}}}}};
}

TEST(MetricsCheck, ToleranceComesFromTheBaselineNoise) {
  json base = results(0.100, 0.010, 0.80);
  // 4 sigma * 1.2533 * 0.01 * sqrt(2/4) = 0.03545 > the 5% floor (0.005).
  EXPECT_TRUE(check_against_baseline(results(0.135, 0.01, 0.80), base).passed);
  CheckOutcome worse = check_against_baseline(results(0.136, 0.01, 0.80), base);
  EXPECT_FALSE(worse.passed);
  EXPECT_EQ(worse.failures, 1);
  EXPECT_NE(worse.table.find("| slc | rmse | 0.1 | 0.136 | +36.00% | 0.035449 | WORSE |"), std::string::npos)
      << worse.table;
  // Better beyond the tolerance passes, but is reported.
  CheckOutcome better = check_against_baseline(results(0.05, 0.01, 0.80), base);
  EXPECT_TRUE(better.passed);
  EXPECT_NE(better.table.find("better"), std::string::npos);
}

TEST(MetricsCheck, ToleranceCountsTheSeedsOfBothSides) {
  // A baseline of 24 seeds, a check of 5: 4 * 1.2533 * 0.01 * sqrt(1/24 + 1/5) = 0.024645.
  json base = results(0.100, 0.010, 0.80, 24);
  EXPECT_TRUE(check_against_baseline(results(0.12464, 0.01, 0.80, 5), base).passed);
  CheckOutcome worse = check_against_baseline(results(0.12465, 0.01, 0.80, 5), base);
  EXPECT_FALSE(worse.passed);
  EXPECT_NE(worse.table.find("| 0.024645 | WORSE |"), std::string::npos) << worse.table;
}

TEST(MetricsCheck, RelativeFloorWithoutNoiseEstimate) {
  json base = results(0.100, 0.0, 0.80, 1);
  EXPECT_TRUE(check_against_baseline(results(0.1049, 0.0, 0.80, 1), base).passed);
  EXPECT_FALSE(check_against_baseline(results(0.1051, 0.0, 0.80, 1), base).passed);
}

TEST(MetricsCheck, SsimDropNonFiniteAndMissingGroupsFail) {
  json base = results(0.1, 0.01, 0.80);
  EXPECT_FALSE(check_against_baseline(results(0.1, 0.01, 0.70), base).passed);
  EXPECT_FALSE(check_against_baseline(results(0.1, 0.01, 0.80, 4, 3), base).passed);
  json empty = {{"groups", json::array()}, {"runs", json::array()}};
  CheckOutcome missing = check_against_baseline(empty, base);
  EXPECT_FALSE(missing.passed);
  EXPECT_NE(missing.table.find("missing"), std::string::npos);
}

// FLIP is recorded beside the gated metrics but never gates: a much worse FLIP passes, and the
// committed baseline (made before FLIP, which it then shows as a dash) still loads and checks.
TEST(MetricsCheck, FlipIsRecordedNeverGatedAndOldBaselinesLoad) {
  json base = results(0.1, 0.01, 0.80), fresh = results(0.1, 0.01, 0.80);
  base["groups"][0]["flip_ldr_median"] = 0.10;
  fresh["groups"][0]["flip_ldr_median"] = 0.30;
  fresh["groups"][0]["flip_hdr_median"] = 0.40;
  CheckOutcome outcome = check_against_baseline(fresh, base);
  EXPECT_TRUE(outcome.passed) << outcome.table;
  EXPECT_NE(outcome.table.find("| slc | flip_ldr | 0.1 | 0.3 | +200.00% | - | recorded |"), std::string::npos) << outcome.table;
  EXPECT_NE(outcome.table.find("| slc | flip_hdr | - | 0.4 | - | - | recorded |"), std::string::npos) << outcome.table;
  EXPECT_EQ(outcome.flip["slc"]["flip_ldr"]["baseline"], 0.10);
  EXPECT_TRUE(outcome.flip["slc"]["flip_hdr"]["baseline"].is_null());

  const json committed = read_json_file(std::string(SST_SOURCE_DIR) + "/results/ci/results.json");
  CheckOutcome same = check_against_baseline(committed, committed);
  EXPECT_TRUE(same.passed) << same.table;
  EXPECT_NE(same.table.find(" | flip_hdr | "), std::string::npos) << same.table;
}

}  // namespace
}  // namespace sst
