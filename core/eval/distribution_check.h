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
//     the median, so that a firefly does not carry it),
//   - the log of the pixel noise: the median over pixels and channels of the squared difference
//     between neighbouring pixels (what regions share, as a VPL set's offset, cancels in it).
// Check, per group: pooled two-sample t-tests (baseline seeds + fresh seeds - 2 degrees of
// freedom) of the same four; the image and block means two-sided (a bias either way), the energy
// and the noise one-sided (a rise in variance, or a bias; a drop of the energy is reported as
// better). A group fails when a p-value is below alpha / 2 over the number of tests of its kind in
// all groups (whole images; blocks): by Bonferroni's inequality clean code fails anywhere with
// probability at most alpha, whatever the correlation between the tests, and the few tests of
// whole images, the most powerful against a uniform bias or a rise in variance, are not diluted
// by the many of blocks. Any non-finite value in a fresh image fails its group.
//
// Same seeds: the baseline also keeps, per group, the reductions of its own renders of the seeds
// a check renders ("same_seeds": each seed's block and image means, error energy and pixel
// noise). A fresh seed with such a record is paired with it, and the log ratios fresh / baseline
// of each value are t-tested (n - 1 degrees of freedom) against a margin of same_seed_margin
// either way (the energy and the noise: a rise only). With the same random numbers every seed's
// ratio is nearly the same, so a bias of a few percent stands out although the VPL set moves a
// whole image by more from seed to seed; a change that makes the random numbers differ spreads
// the ratios as widely as the estimates, which keeps the test valid and weakens it to about the
// two-sample tests' power. The margin keeps float rounding (another CPU's Embree kernels or libm)
// from counting as a change. These tests count with the others of their kind in the thresholds.
//
// | parameter        | default | meaning                                                             |
// |------------------|---------|---------------------------------------------------------------------|
// | alpha            | 1e-3    | probability that clean code fails the check (all groups together)   |
// | block            | 16      | block side in pixels (baseline only; the check uses the baseline's) |
// | inject_bias      | 0       | fault for measuring power: fresh colour += inject_bias x its        |
// |                  |         | "indirect" layer (a uniform relative bias of the indirect estimate) |
// | inject_variance  | 0       | fault: fresh colour += normal noise of inject_variance x the        |
// |                  |         | baseline's per-pixel variance (a relative rise in variance)         |
// | inject_method    | ""      | inject only into groups of this method ("": all groups)             |
// | same_seed_margin | 0.005   | same seeds: the relative change below which a ratio is no change    |
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
  double same_seed_margin = 0.005;
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
  // absolute), block_p, failing_blocks, energy_ratio, energy_p, noise_ratio, noise_p, same_seeds (pairs tested), and
  // where tested same_seeds_largest (the value with the smallest p), same_seeds_change (its
  // relative change), same_seeds_t, same_seeds_p, same_seeds_failing.
  nlohmann::json groups = nlohmann::json::array();
  // The fresh runs' own same-seed records, by group: a baseline's "same_seeds" for later checks
  // of these seeds (a power study pairs its faulty checks with its clean one).
  nlohmann::json same_seeds = nlohmann::json::object();
};

// Adds to each group of `statistics` (the JSON above, its images already under `baseline_dir`) the
// same-seed records of the runs of that group in `results` (a sweep of the seeds a check renders,
// with its runs in `results_dir`). Throws sst::Error for a run whose image is not finite or not of
// the statistics' size.
void add_same_seed_records(nlohmann::json& statistics, const nlohmann::json& results, const std::string& results_dir,
                           const std::string& baseline_dir);

// Tests the fresh runs (`fresh`, with images in `fresh_dir`) against `statistics` (the JSON above)
// and the images under `baseline_dir`.
DistributionOutcome check_distribution(const nlohmann::json& fresh, const std::string& fresh_dir,
                                       const nlohmann::json& statistics, const std::string& baseline_dir,
                                       const DistributionParams& params = {});

}  // namespace sst
