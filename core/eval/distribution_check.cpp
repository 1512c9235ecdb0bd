// The distribution check (distribution_check.h): each baseline group's fresh seeds loaded and
// reduced, tested against the baseline's statistics (two-sample tests) and against its renders
// of the same seeds (same-seed tests), and the verdicts written as a table and as JSON.
#include "core/eval/distribution_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "core/eval/distribution_baseline.h"
#include "core/eval/distribution_stats.h"
#include "core/eval/json_fields.h"
#include "core/image/image.h"
#include "core/math/student_t.h"
#include "core/util/error.h"
#include "core/util/hash.h"
#include "core/util/json_io.h"

namespace sst {
namespace {
namespace fs = std::filesystem;
using namespace distribution;

std::string fmt(const char* format, double v) {
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// Faults injected into a fresh image (DistributionParams), from a generator seeded per group and
// seed so that a check repeats exactly.
void inject(Image& color, const std::string& path, const Image& base_variance, const DistributionParams& p,
            uint64_t rng_seed) {
  if (p.inject_bias != 0.0) {
    const Image indirect = read_layer(path, "indirect");
    if (indirect.width != color.width || indirect.height != color.height)
      throw Error("cannot inject a bias into " + path + ": its indirect layer has another size");
    for (size_t i = 0; i < color.pixel_count(); ++i)
      for (int c = 0; c < kChannels; ++c)
        color.data[i * color.channels + c] += float(p.inject_bias * indirect.data[i * indirect.channels + c]);
  }
  if (p.inject_variance > 0.0) {
    std::mt19937_64 rng(rng_seed);
    std::normal_distribution<double> normal;
    for (size_t i = 0; i < color.pixel_count(); ++i)
      for (int c = 0; c < kChannels; ++c)
        color.data[i * color.channels + c] +=
            float(std::sqrt(p.inject_variance * double(base_variance.data[i * base_variance.channels + c])) * normal(rng));
  }
}

// One baseline group's results: a row of the table and an entry of DistributionOutcome::groups.
struct Row {
  std::string group, method;
  std::string problem;  // why the group fails without a test ("" when tested)
  bool missing = false;
  int seeds_base = 0, seeds_fresh = 0;
  TTest image, worst_block, energy, energy_lower, noise;
  int image_channel = 0;
  std::vector<double> block_p;
  double energy_ratio = NAN, noise_ratio = NAN;
  // Same seeds (tested when at least 2 fresh seeds have a baseline record).
  int same_n = 0;
  MarginTest same_worst;  // the value with the smallest p
  std::string same_worst_what;
  std::vector<double> same_whole_p, same_block_p;
};

// The baseline's statistics of one group, read and checked.
struct BaselineGroup {
  int seeds = 0;
  int width = 0, height = 0;
  size_t blocks = 0;
  Image mean, variance;  // per pixel, over seeds
  std::vector<double> block_mean, block_variance, image_mean, image_variance;
};

// The fresh seeds of a group, reduced.
struct FreshSeeds {
  std::vector<Reduction> reductions;
  std::vector<double> energies;  // log_energy against the baseline's mean
};

// Reads, checks and reduces the fresh seeds of `g`, with the faults of `p` injected where they
// apply, and adds each seed's same-seed record to `same_seeds`. Returns why the group fails
// without a test: a seed of another size than the baseline's, or not finite ("" when all are
// usable).
std::string load_fresh_seeds(const GroupRuns& g, const BaselineGroup& base, int block, const DistributionParams& p,
                             FreshSeeds& fresh, nlohmann::json& same_seeds) {
  const bool injected = p.inject_method.empty() || p.inject_method == g.method;
  for (size_t s = 0; s < g.images.size(); ++s) {
    Image im = read_image(g.images[s]);
    if (im.width != base.width || im.height != base.height)
      return "fresh images are " + std::to_string(im.width) + "x" + std::to_string(im.height) + ", the baseline's " +
             std::to_string(base.width) + "x" + std::to_string(base.height);
    if (!all_finite(im)) return "non-finite values in " + g.images[s];
    if (injected) inject(im, g.images[s], base.variance, p, Hash64().add(g.group).value() + s);
    fresh.reductions.push_back(reduce(im, block));
    fresh.energies.push_back(log_energy(im, base.mean, 1.0));
    if (std::isfinite(g.seeds[s]))
      same_seeds[g.group].push_back(same_seed_record(g.seeds[s], fresh.reductions.back(), fresh.energies.back()));
  }
  return "";
}

// The pooled two-sample tests of the fresh seeds against the baseline's statistics `b`: the image
// mean per channel and the block means two-sided, the error energy and the pixel noise one-sided.
// Returns whether the pixel noise was tested (baselines made before the pixel-noise statistics
// have none to test against).
bool two_sample_tests(const nlohmann::json& b, const BaselineGroup& base, const FreshSeeds& fresh, Row& row) {
  const int n_base = base.seeds, n = row.seeds_fresh;
  const std::vector<Reduction>& reductions = fresh.reductions;
  for (int c = 0; c < kChannels; ++c) {
    const MeanVariance fresh_mean = over_seeds(reductions, [c](const Reduction& r) { return r.image[c]; });
    const TTest t = pooled_t({base.image_mean[c], base.image_variance[c]}, n_base, fresh_mean, n, false);
    if (c == 0 || t.p < row.image.p) row.image = t, row.image_channel = c;
  }
  for (size_t k = 0; k < base.blocks * kChannels; ++k) {
    const MeanVariance fresh_mean = over_seeds(reductions, [k](const Reduction& r) { return r.blocks[k]; });
    const TTest t = pooled_t({base.block_mean[k], base.block_variance[k]}, n_base, fresh_mean, n, false);
    row.block_p.push_back(t.p);
    if (k == 0 || t.p < row.worst_block.p) row.worst_block = t;
  }
  const MeanVariance e_base{number(b, "log_energy_mean"), number(b, "log_energy_variance")};
  const MeanVariance e_fresh = mean_variance(fresh.energies);
  row.energy = pooled_t(e_base, n_base, e_fresh, n, true);
  row.energy_lower = {row.energy.t, student_t_upper_p(-row.energy.t, double(n_base + n - 2))};
  row.energy_ratio = std::exp(e_fresh.mean - e_base.mean);
  const MeanVariance noise_base{number(b, "log_noise_mean"), number(b, "log_noise_variance")};
  if (!(std::isfinite(noise_base.mean) && std::isfinite(noise_base.variance))) return false;
  const MeanVariance noise_fresh = over_seeds(reductions, [](const Reduction& r) { return r.log_noise; });
  row.noise = pooled_t(noise_base, n_base, noise_fresh, n, true);
  row.noise_ratio = std::exp(noise_fresh.mean - noise_base.mean);
  return true;
}

// Pairs each fresh seed with the baseline's record of that seed and tests the log ratios of the
// image means, the block means, the error energies and the pixel noise (margin_t).
void same_seed_tests(Row& row, const GroupRuns& g, const FreshSeeds& fresh_seeds, const std::vector<SameSeedRecord>& base,
                     int blocks_x, const DistributionParams& p) {
  const std::vector<Reduction>& fresh = fresh_seeds.reductions;
  std::vector<std::pair<const Reduction*, const Reduction*>> pairs;  // fresh, baseline
  std::vector<double> energy_ratios, noise_ratios;
  for (size_t s = 0; s < fresh.size(); ++s)
    for (const SameSeedRecord& r : base)
      if (r.seed == g.seeds[s]) {
        pairs.push_back({&fresh[s], &r.reduction});
        energy_ratios.push_back(fresh_seeds.energies[s] - r.log_energy);
        noise_ratios.push_back(fresh[s].log_noise - r.reduction.log_noise);
        break;
      }
  row.same_n = int(pairs.size());
  if (pairs.size() < 2) return;
  const double margin = std::log1p(p.same_seed_margin);
  auto consider = [&row](const MarginTest& m, const std::string& what) {
    if (row.same_worst_what.empty() || m.t.p < row.same_worst.t.p) row.same_worst = m, row.same_worst_what = what;
  };
  std::array<double, kChannels> floor{};
  for (int c = 0; c < kChannels; ++c) {
    for (const auto& [f, b] : pairs) floor[c] += 1e-3 * b->image[c] / double(pairs.size());
    floor[c] = std::max(floor[c], 1e-12);
  }
  auto log_ratios = [&](auto value, double fl) {  // value(const Reduction&)
    std::vector<double> d;
    for (const auto& [f, b] : pairs) d.push_back(log_above(value(*f), fl) - log_above(value(*b), fl));
    return d;
  };
  for (int c = 0; c < kChannels; ++c) {
    const MarginTest m = margin_t(log_ratios([c](const Reduction& r) { return r.image[c]; }, floor[c]), margin, false);
    row.same_whole_p.push_back(m.t.p);
    consider(m, std::string("image ") + "RGB"[c]);
  }
  for (size_t k = 0; k < pairs[0].second->blocks.size(); ++k) {
    const int c = int(k % kChannels);
    double base_mean = 0.0;
    for (const auto& [f, b] : pairs) base_mean += b->blocks[k] / double(pairs.size());
    if (!(base_mean > floor[c])) continue;  // a black block has no ratio to test
    const MarginTest m = margin_t(log_ratios([k](const Reduction& r) { return r.blocks[k]; }, floor[c]), margin, false);
    row.same_block_p.push_back(m.t.p);
    const int index = int(k / kChannels);
    consider(m, "block (" + std::to_string(index % blocks_x) + "," + std::to_string(index / blocks_x) + ") " + "RGB"[c]);
  }
  const MarginTest e = margin_t(energy_ratios, margin, true);
  row.same_whole_p.push_back(e.t.p);
  consider(e, "error energy");
  const MarginTest noise = margin_t(noise_ratios, margin, true);
  row.same_whole_p.push_back(noise.t.p);
  consider(noise, "pixel noise");
}

// Tests the fresh seeds of baseline group `b` and counts its tests into `out` (and its seeds'
// records into out.same_seeds).
Row test_group(const nlohmann::json& b, const std::map<std::string, GroupRuns>& fresh_groups, const std::string& baseline_dir,
               int block, const DistributionParams& p, DistributionOutcome& out) {
  Row row;
  row.group = b.value("group", "");
  row.method = b.value("method", "");
  BaselineGroup base;
  base.seeds = whole_number(b, "seeds", 2, 1 << 20);
  base.width = whole_number(b, "width", 1, 1 << 16), base.height = whole_number(b, "height", 1, 1 << 16);
  row.seeds_base = base.seeds;
  base.blocks = size_t(blocks_across(base.width, block)) * blocks_across(base.height, block);
  out.whole_image_tests += kChannels + 1;
  out.block_tests += int(base.blocks) * kChannels;
  auto it = fresh_groups.find(row.group);
  if (it == fresh_groups.end()) {
    row.problem = "missing from the fresh results";
    row.missing = true;
    return row;
  }
  const GroupRuns& g = it->second;
  row.seeds_fresh = int(g.images.size());
  if (row.seeds_fresh < 1) {
    row.problem = "no fresh seeds";
    return row;
  }
  const std::string images = (fs::path(baseline_dir) / b.value("images", "")).string();
  base.mean = read_image(images);
  base.variance = read_layer(images, "variance");
  base.block_mean = doubles(b, row.group, "block_mean", base.blocks * kChannels);
  base.block_variance = doubles(b, row.group, "block_variance", base.blocks * kChannels);
  base.image_mean = doubles(b, row.group, "image_mean", kChannels);
  base.image_variance = doubles(b, row.group, "image_variance", kChannels);
  FreshSeeds fresh;
  row.problem = load_fresh_seeds(g, base, block, p, fresh, out.same_seeds);
  if (!row.problem.empty()) return row;
  if (two_sample_tests(b, base, fresh, row)) out.whole_image_tests += 1;
  same_seed_tests(row, g, fresh, same_seed_records(b, row.group, base.blocks * kChannels), blocks_across(base.width, block),
                  p);
  out.whole_image_tests += int(row.same_whole_p.size());
  out.block_tests += int(row.same_block_p.size());
  return row;
}

// A tested row's verdict against the thresholds of all groups.
struct Verdict {
  int failing_blocks = 0;
  int same_failing = 0;
  bool fails = false;
  bool better = false;  // passes, and the error energy dropped significantly
};

Verdict verdict(const Row& row, const DistributionOutcome& out) {
  auto below = [](const std::vector<double>& ps, double threshold) {
    return int(std::count_if(ps.begin(), ps.end(), [&](double q) { return !(q >= threshold); }));
  };
  Verdict v;
  v.failing_blocks = below(row.block_p, out.block_threshold);
  v.same_failing = below(row.same_whole_p, out.whole_image_threshold) + below(row.same_block_p, out.block_threshold);
  v.fails = !(row.image.p >= out.whole_image_threshold) || v.failing_blocks > 0 ||
            !(row.energy.p >= out.whole_image_threshold) || !(row.noise.p >= out.whole_image_threshold) ||
            v.same_failing > 0;
  v.better = !v.fails && row.energy_lower.p < out.whole_image_threshold;
  return v;
}

const char* status(const Verdict& v) { return v.fails ? "fails" : v.better ? "better" : "ok"; }

// The Markdown row of a tested group.
std::string table_row(const Row& row, const Verdict& v) {
  std::ostringstream t;
  const char channel = "RGB"[row.image_channel];
  t << "| " << row.group << " | " << row.seeds_base << ", " << row.seeds_fresh << " | " << channel
    << " " << fmt("%+.2f", row.image.t) << " (" << fmt("%.2g", row.image.p) << ") | "
    << fmt("%.2f", std::abs(row.worst_block.t)) << " (" << fmt("%.2g", row.worst_block.p) << "), " << v.failing_blocks
    << " | " << fmt("%.3f", row.energy_ratio) << " (" << fmt("%.2g", row.energy.p) << ") | ";
  if (std::isfinite(row.noise_ratio))
    t << fmt("%.3f", row.noise_ratio) << " (" << fmt("%.2g", row.noise.p) << ") | ";
  else
    t << "- | ";
  if (row.same_worst_what.empty())
    t << row.same_n << ", -";
  else
    t << row.same_n << ", " << row.same_worst_what << " " << fmt("%+.2f%%", 100.0 * std::expm1(row.same_worst.change))
      << ", " << fmt("%.3g", row.same_worst.t.t) << " (" << fmt("%.2g", row.same_worst.t.p) << "), " << v.same_failing;
  t << " | " << (v.fails ? "FAILS" : v.better ? "better" : "ok") << " |\n";
  return t.str();
}

// The entry of DistributionOutcome::groups of a tested group (non-finite values as null).
nlohmann::json group_json(const Row& row, const Verdict& v) {
  nlohmann::json g = {{"group", row.group}, {"method", row.method}, {"seeds_baseline", row.seeds_base},
                      {"seeds_fresh", row.seeds_fresh}};
  g["status"] = status(v);
  g["image_t"] = number_or_null(row.image.t);
  g["image_p"] = row.image.p;
  g["block_t"] = number_or_null(std::abs(row.worst_block.t));
  g["block_p"] = row.worst_block.p;
  g["failing_blocks"] = v.failing_blocks;
  g["energy_ratio"] = number_or_null(row.energy_ratio);
  g["energy_p"] = row.energy.p;
  g["noise_ratio"] = number_or_null(row.noise_ratio);
  g["noise_p"] = row.noise.p;
  g["same_seeds"] = row.same_n;
  if (!row.same_worst_what.empty()) {
    g["same_seeds_largest"] = row.same_worst_what;
    g["same_seeds_change"] = number_or_null(std::expm1(row.same_worst.change));
    g["same_seeds_t"] = number_or_null(row.same_worst.t.t);
    g["same_seeds_p"] = row.same_worst.t.p;
    g["same_seeds_failing"] = v.same_failing;
  }
  return g;
}

// Adds a group's row to the table `t` and its entry to out.groups, and counts its failure.
void report_row(const Row& row, DistributionOutcome& out, std::ostringstream& t) {
  if (!row.problem.empty()) {
    out.groups.push_back({{"group", row.group}, {"method", row.method}, {"seeds_baseline", row.seeds_base},
                          {"seeds_fresh", row.seeds_fresh}, {"status", row.missing ? "missing" : "fails"},
                          {"problem", row.problem}});
    t << "| " << row.group << " | " << row.seeds_base << ", " << row.seeds_fresh << " | - | - | - | - | - | FAILS: "
      << row.problem << " |\n";
    ++out.failures;
    return;
  }
  const Verdict v = verdict(row, out);
  t << table_row(row, v);
  if (v.fails) ++out.failures;
  out.groups.push_back(group_json(row, v));
}

}  // namespace

DistributionOutcome check_distribution(const nlohmann::json& fresh, const std::string& fresh_dir,
                                       const nlohmann::json& statistics, const std::string& baseline_dir,
                                       const DistributionParams& p) {
  DistributionOutcome out;
  const int block = whole_number(statistics, "block", 1, 4096);
  std::map<std::string, GroupRuns> fresh_groups;
  for (GroupRuns& g : group_runs(fresh, fresh_dir)) fresh_groups[g.group] = std::move(g);
  std::vector<Row> rows;
  for (const nlohmann::json& b : member(statistics, "groups"))
    rows.push_back(test_group(b, fresh_groups, baseline_dir, block, p, out));

  // Half of alpha for the tests of whole images (the most powerful against a uniform bias or a rise
  // in variance), half for the many block tests.
  out.whole_image_threshold = 0.5 * p.alpha / std::max(out.whole_image_tests, 1);
  out.block_threshold = 0.5 * p.alpha / std::max(out.block_tests, 1);
  std::ostringstream t;
  t << "| group | seeds (baseline, fresh) | image mean: t (p) | blocks: largest abs t (p), failing | "
       "error energy: fresh / baseline (p) | pixel noise: fresh / baseline (p) | "
       "same seeds: n, largest change, t (p), failing | status |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  for (const Row& row : rows) report_row(row, out, t);
  for (const auto& [name, g] : fresh_groups) {
    const bool known = std::any_of(rows.begin(), rows.end(), [&n = name](const Row& r) { return r.group == n; });
    if (!known) t << "| " << name << " | -, " << g.images.size() << " | not in the baseline | - | - | - | - | ok |\n";
  }
  out.passed = out.failures == 0;
  t << "\nA group fails when a p-value is below alpha/2 over the number of tests of its kind: "
    << fmt("%.3g", out.whole_image_threshold) << " for the " << out.whole_image_tests
    << " tests of whole images (mean per channel, error energy, pixel noise), " << fmt("%.3g", out.block_threshold)
    << " for the "
    << out.block_tests << " block tests (alpha " << fmt("%.3g", p.alpha) << "); each kind counts the same-seed tests "
    << "too, which compare a fresh seed with the baseline's render of that seed beyond a margin of "
    << fmt("%.3g", 100.0 * p.same_seed_margin) << "%.\n";
  out.table = t.str();
  return out;
}

}  // namespace sst
