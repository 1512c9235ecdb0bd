// `sst-eval check`: the CI metrics check. Fresh results of configs/ci.json are compared with the
// committed baseline (results/ci/results.json); a group fails when an error metric is worse than
// its baseline by more than the tolerance derived from the baseline's own run-to-run noise.
//
// | option        | default | meaning                                                               |
// |---------------|---------|-----------------------------------------------------------------------|
// | sigmas        | 4       | allowed change in standard errors of the difference of two medians:   |
// |               |         | sigmas * 1.2533 * robust_std * sqrt(1/seeds + 1/fresh seeds)          |
// | min_relative  | 0.05    | and never less than this fraction of the baseline value, so that a    |
// |               |         | noise estimate from few seeds cannot make the check flaky              |
//
// Checked per group, on medians over seeds (one seed hit by a rare firefly must not move the
// check, nor widen its tolerance): rmse (lower is better) and 1 - ssim; the noise is the
// baseline's robust std (1.4826 x median absolute deviation over its seeds). Any non-finite
// sample in a fresh run fails. Improvements beyond the tolerance are reported (time to update
// the baseline) but pass. Times are shown, never gated; so are the medians of LDR-FLIP and
// HDR-FLIP (core/metrics/flip.h), which are recorded (a baseline made before FLIP has none) but
// never fail the check.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace sst {

struct CheckParams {
  double sigmas = 4.0;
  double min_relative = 0.05;
};

struct CheckOutcome {
  bool passed = true;
  int failures = 0;
  std::string table;  // Markdown: every group and metric, what moved marked
  // Per group: {"flip_ldr": {"baseline": median or null, "fresh": median or null}, "flip_hdr": ...}.
  nlohmann::json flip = nlohmann::json::object();
};

CheckOutcome check_against_baseline(const nlohmann::json& fresh, const nlohmann::json& baseline,
                                    const CheckParams& params = {});

}  // namespace sst
