// The distribution check of `sst-eval check`: do fresh renders of each group (a run without its
// seed) come from the same distribution as the baseline's? Seeds are the independent samples, so
// the tests hold for methods whose pixels share randomness (a VPL set) as well as for those whose
// pixels are independent. It sits beside the median-RMSE table (metrics_check.h), which cannot
// see a regression smaller than the seed-to-seed spread of the RMSE.
//
// Baseline (`sst-eval check --update`, usually with more seeds than a check renders), per group,
// over its seeds: the mean and variance images (statistics/<group>.exr: RGB mean, layer
// "variance"), and in check_statistics.json the mean and variance over seeds of
//   - each block's mean, per channel (blocks of `block` x `block` pixels),
//   - the whole image's mean, per channel,
//   - the log of the error energy: the median over pixels and channels of (image - baseline mean)^2
//     (for a baseline seed, against the mean of the other seeds, so that both have the same scale;
//     the median, so that a firefly does not carry it).
// Check, per group: pooled two-sample t-tests (baseline seeds + fresh seeds - 2 degrees of
// freedom) of the same three; the image and block means two-sided (a bias either way), the energy
// one-sided (a rise in variance, or a bias; a drop is reported as better). A group fails when a
// p-value is below alpha / 2 over the number of tests of its kind in all groups (whole images;
// blocks): by Bonferroni's inequality clean code fails anywhere with probability at most alpha,
// whatever the correlation between the tests, and the few tests of whole images, the most
// powerful against a uniform bias or a rise in variance, are not diluted by the many of blocks.
// Any non-finite value in a fresh image fails its group.
//
// | parameter       | default | meaning                                                             |
// |-----------------|---------|---------------------------------------------------------------------|
// | alpha           | 1e-3    | probability that clean code fails the check (all groups together)   |
// | block           | 16      | block side in pixels (baseline only; the check uses the baseline's) |
// | inject_bias     | 0       | fault for measuring power: fresh colour += inject_bias x its        |
// |                 |         | "indirect" layer (a uniform relative bias of the indirect estimate) |
// | inject_variance | 0       | fault: fresh colour += normal noise of inject_variance x the        |
// |                 |         | baseline's per-pixel variance (a relative rise in variance)          |
// | inject_method   | ""      | inject only into groups of this method ("": all groups)             |
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace sst {

struct DistributionParams {
  double alpha = 1e-3;
  int block = 16;
  double inject_bias = 0.0;
  double inject_variance = 0.0;
  std::string inject_method;
};

// Reduces the runs of `results` (results.json of a sweep whose runs are in `results_dir`) to the
// statistics above; writes the images under `baseline_dir`/statistics/ and returns the JSON that
// the caller stores as `baseline_dir`/check_statistics.json. Throws sst::Error for a group with
// fewer than 2 seeds or runs without an EXR image.
nlohmann::json make_distribution_baseline(const nlohmann::json& results, const std::string& results_dir,
                                          const std::string& baseline_dir, const DistributionParams& params = {});

struct DistributionOutcome {
  bool passed = true;
  int failures = 0;
  int whole_image_tests = 0;        // over all groups: image mean per channel and error energy
  int block_tests = 0;              // over all groups: block means per channel
  double whole_image_threshold = 0; // alpha / 2 / whole_image_tests
  double block_threshold = 0;       // alpha / 2 / block_tests
  std::string table;        // Markdown: one row per group
  // Per group: group, method, status ("ok", "fails", "better", "missing"), problem (why a group
  // failed without a test), seeds_baseline, seeds_fresh, image_t, image_p, block_t (largest
  // absolute), block_p, failing_blocks, energy_ratio, energy_p.
  nlohmann::json groups = nlohmann::json::array();
};

// Tests the fresh runs (`fresh`, with images in `fresh_dir`) against `statistics` (the JSON above)
// and the images under `baseline_dir`.
DistributionOutcome check_distribution(const nlohmann::json& fresh, const std::string& fresh_dir,
                                       const nlohmann::json& statistics, const std::string& baseline_dir,
                                       const DistributionParams& params = {});

}  // namespace sst
