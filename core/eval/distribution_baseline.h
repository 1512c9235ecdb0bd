// What a distribution check reads besides fresh images: a sweep's runs by group, and the
// baseline's statistics JSON (check_statistics.json) with its same-seed records. The baseline is
// made once and kept (make_distribution_baseline and add_same_seed_records in
// distribution_baseline.cpp, declared in distribution_check.h); every check reads it back here,
// checking each value before it is used.
#pragma once
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "core/eval/distribution_stats.h"

namespace sst::distribution {

struct GroupRuns {
  std::string group;
  std::string method;
  std::vector<std::string> images;  // the EXR of each seed
  std::vector<double> seeds;        // each run's params.seed (NaN where a run has none)
};

// The groups of `results` (results.json of a sweep whose runs are in `dir`); throws sst::Error for
// a run the results lack or one without an EXR image.
std::vector<GroupRuns> group_runs(const nlohmann::json& results, const std::string& dir);

// A whole number of the statistics JSON, checked before it is converted.
int whole_number(const nlohmann::json& j, const char* key, int lo, int hi);

// The `size` numbers of j[key] for group `group`; throws sst::Error for another count.
std::vector<double> doubles(const nlohmann::json& j, const std::string& group, const char* key, size_t size);

// A seed's reduction and error energy as a record of a group's "same_seeds".
nlohmann::json same_seed_record(double seed, const Reduction& r, double log_energy);

// A baseline record, checked against the group's sizes.
struct SameSeedRecord {
  double seed = NAN;
  Reduction reduction;
  double log_energy = NAN;
};

// The same-seed records of baseline group `group` (named `name`), each with `block_values` block
// means; throws sst::Error for a record of other sizes or without finite values.
std::vector<SameSeedRecord> same_seed_records(const nlohmann::json& group, const std::string& name, size_t block_values);

}  // namespace sst::distribution
