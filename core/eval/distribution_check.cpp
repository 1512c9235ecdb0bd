#include "core/eval/distribution_check.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <glm/gtc/packing.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <vector>

#include "core/eval/json_fields.h"
#include "core/image/image.h"
#include "core/math/student_t.h"
#include "core/util/hash.h"
#include "core/util/error.h"

namespace sst {
namespace fs = std::filesystem;
namespace {

constexpr int kChannels = 3;

struct GroupRuns {
  std::string group;
  std::string method;
  std::vector<std::string> images;  // the EXR of each seed
  std::vector<double> seeds;        // each run's params.seed (NaN where a run has none)
};

std::vector<GroupRuns> group_runs(const nlohmann::json& results, const std::string& dir) {
  std::map<std::string, const nlohmann::json*> runs;
  for (const nlohmann::json& r : results.at("runs")) runs[r.value("id", "")] = &r;
  std::vector<GroupRuns> out;
  for (const nlohmann::json& g : results.at("groups")) {
    GroupRuns group{g.value("group", ""), g.value("method", ""), {}, {}};
    for (const nlohmann::json& id : member(g, "runs")) {
      auto it = runs.find(id.is_string() ? id.get<std::string>() : "");
      if (it == runs.end()) throw Error("group '" + group.group + "' lists run " + id.dump() + ", which the results lack");
      const nlohmann::json& exr = member(member(*it->second, "images"), "exr");
      if (!exr.is_string())
        throw Error("group '" + group.group + "': run " + id.dump() + " has no EXR image to take statistics of");
      group.images.push_back((fs::path(dir) / exr.get<std::string>()).string());
      group.seeds.push_back(number(member(*it->second, "params"), "seed"));
    }
    out.push_back(std::move(group));
  }
  return out;
}

// One seed's image reduced to what the tests compare.
struct Reduction {
  std::vector<double> blocks;             // [block * 3 + channel]: the block's mean
  std::array<double, kChannels> image{};  // the whole image's mean
  double log_noise = 0.0;                 // pixel_noise()
};

int blocks_across(int pixels, int block) { return (pixels + block - 1) / block; }

// The median of `squares` (reordered), 0 when empty.
double median_of(std::vector<double>& squares) {
  if (squares.empty()) return 0.0;
  auto middle = squares.begin() + squares.size() / 2;
  std::nth_element(squares.begin(), middle, squares.end());
  return *middle;
}

// The log of the median over pixels and channels of the squared differences between horizontal
// and vertical neighbours: the image's pixel-to-pixel noise. Unlike the error energy it ignores
// what whole regions share (a VPL set's offset, a radiance cache's blotches), which varies from
// seed to seed by far more than a 50% rise in pixel variance.
double pixel_noise(const Image& im) {
  std::vector<double> squares;
  squares.reserve(im.pixel_count() * 2 * kChannels);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < kChannels; ++c) {
        const double v = im.at(x, y, c);
        if (x + 1 < im.width) squares.push_back((im.at(x + 1, y, c) - v) * (im.at(x + 1, y, c) - v));
        if (y + 1 < im.height) squares.push_back((im.at(x, y + 1, c) - v) * (im.at(x, y + 1, c) - v));
      }
  return std::log(std::max(median_of(squares), 1e-300));
}

Reduction reduce(const Image& im, int block) {
  const int bx = blocks_across(im.width, block), by = blocks_across(im.height, block);
  Reduction r;
  r.blocks.assign(size_t(bx) * by * kChannels, 0.0);
  std::vector<double> counts(size_t(bx) * by, 0.0);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const size_t b = size_t(y / block) * bx + size_t(x / block);
      counts[b] += 1.0;
      for (int c = 0; c < kChannels; ++c) {
        r.blocks[b * kChannels + c] += im.at(x, y, c);
        r.image[c] += im.at(x, y, c);
      }
    }
  for (size_t b = 0; b < counts.size(); ++b)
    for (int c = 0; c < kChannels; ++c) r.blocks[b * kChannels + c] /= counts[b];
  for (int c = 0; c < kChannels; ++c) r.image[c] /= double(im.pixel_count());
  r.log_noise = pixel_noise(im);
  return r;
}

// The median over pixels and channels of (image - mean)^2, times `scale`, as a log. The median,
// not the mean: one firefly would otherwise carry a seed's energy (and the spread of the energies
// over seeds), and the log because energies are closer to normal in it.
double log_energy(const Image& im, const Image& mean, double scale) {
  std::vector<double> squares;
  squares.reserve(im.pixel_count() * kChannels);
  for (size_t i = 0; i < im.pixel_count(); ++i)
    for (int c = 0; c < kChannels; ++c) {
      const double d = double(im.data[i * im.channels + c]) - double(mean.data[i * mean.channels + c]);
      squares.push_back(d * d);
    }
  return std::log(std::max(scale * median_of(squares), 1e-300));
}

struct MeanVariance {
  double mean = 0.0;
  double variance = 0.0;  // unbiased
};

MeanVariance mean_variance(const std::vector<double>& v) {
  MeanVariance m;
  for (double x : v) m.mean += x;
  m.mean /= double(v.size());
  for (double x : v) m.variance += (x - m.mean) * (x - m.mean);
  m.variance = v.size() > 1 ? m.variance / double(v.size() - 1) : 0.0;
  return m;
}

// The mean and variance over seeds of one value of their reductions.
template <class Value>
MeanVariance over_seeds(const std::vector<Reduction>& reductions, Value value) {
  std::vector<double> v;
  for (const Reduction& r : reductions) v.push_back(value(r));
  return mean_variance(v);
}

// statistics/<group>.exr: the group's name with every run of other characters than letters and
// digits as one '-'.
std::string file_stem(const std::string& group) {
  std::string out;
  for (char ch : group) {
    if (std::isalnum(static_cast<unsigned char>(ch))) out.push_back(char(std::tolower(static_cast<unsigned char>(ch))));
    else if (!out.empty() && out.back() != '-') out.push_back('-');
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "group" : out;
}

std::vector<float> to_floats(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

std::vector<double> doubles(const nlohmann::json& j, const std::string& group, const char* key, size_t size) {
  const nlohmann::json& a = member(j, key);
  if (!a.is_array() || a.size() != size)
    throw Error("check statistics of group '" + group + "': '" + key + "' must hold " + std::to_string(size) + " numbers");
  std::vector<double> out;
  for (const nlohmann::json& v : a) out.push_back(number(v));
  return out;
}

struct TTest {
  double t = 0.0;
  double p = 1.0;
};

// Pooled two-sample t-test of a fresh sample (mean, variance, n) against the baseline's;
// `one_sided`: only a larger fresh mean is significant.
TTest pooled_t(const MeanVariance& base, int n_base, const MeanVariance& fresh, int n_fresh, bool one_sided) {
  const double df = double(n_base + n_fresh - 2);
  const double pooled = ((n_base - 1) * base.variance + (n_fresh - 1) * fresh.variance) / df;
  const double se = std::sqrt(pooled * (1.0 / n_base + 1.0 / n_fresh));
  const double diff = fresh.mean - base.mean;
  TTest r;
  if (!std::isfinite(diff)) r.t = NAN;
  else if (se > 0.0) r.t = diff / se;
  else r.t = diff == 0.0 ? 0.0 : std::copysign(INFINITY, diff);
  if (std::isnan(r.t)) r.p = 0.0;  // a non-finite fresh value fails
  else r.p = one_sided ? student_t_upper_p(r.t, df) : student_t_two_sided_p(r.t, df);
  return r;
}

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

// A whole number of the statistics JSON, checked before it is converted.
int whole_number(const nlohmann::json& j, const char* key, int lo, int hi) {
  const double v = number(j, key);
  if (!(v >= lo && v <= hi) || v != std::floor(v))
    throw Error(std::string("check statistics: '") + key + "' must be a whole number in " + std::to_string(lo) + ".." +
                std::to_string(hi));
  return int(v);
}

bool all_finite(const Image& im) {
  return std::all_of(im.data.begin(), im.data.end(), [](float v) { return std::isfinite(v); });
}

// A seed's reduction and error energy as a record of a group's "same_seeds".
nlohmann::json same_seed_record(double seed, const Reduction& r, double log_energy) {
  return {{"seed", seed},
          {"image", std::vector<double>(r.image.begin(), r.image.end())},
          {"blocks", to_floats(r.blocks)},
          {"log_energy", log_energy},
          {"log_noise", r.log_noise}};
}

// A baseline record, checked against the group's sizes.
struct SameSeedRecord {
  double seed = NAN;
  Reduction reduction;
  double log_energy = NAN;
};

std::vector<SameSeedRecord> same_seed_records(const nlohmann::json& group, const std::string& name, size_t block_values) {
  std::vector<SameSeedRecord> out;
  for (const nlohmann::json& r : member(group, "same_seeds")) {
    SameSeedRecord rec;
    rec.seed = number(r, "seed");
    const std::vector<double> image = doubles(r, name, "image", kChannels);
    std::copy(image.begin(), image.end(), rec.reduction.image.begin());
    rec.reduction.blocks = doubles(r, name, "blocks", block_values);
    rec.reduction.log_noise = number(r, "log_noise");
    rec.log_energy = number(r, "log_energy");
    if (!std::isfinite(rec.seed) || !std::isfinite(rec.log_energy) || !std::isfinite(rec.reduction.log_noise))
      throw Error("check statistics of group '" + name +
                  "': a same-seed record needs a finite seed, log_energy and log_noise");
    out.push_back(std::move(rec));
  }
  return out;
}

// The same-seed test of one value: are the fresh values' log ratios to the baseline's, seed by
// seed, further from 0 than `margin` beyond their noise? A t-test of the mean ratio against the
// margin (n - 1 degrees of freedom): with the same random numbers the ratios are nearly equal
// over seeds, so a change of a few percent stands out even where the seed-to-seed spread is far
// larger; where a change has made the random numbers differ, the ratios spread like the estimates
// and the test is as valid, and weaker. The margin keeps float rounding (another CPU's Embree
// kernels or libm) from counting as a change. `one_sided`: only a rise counts.
struct MarginTest {
  double change = 0.0;  // the mean log ratio
  TTest t;
};

MarginTest margin_t(const std::vector<double>& log_ratios, double margin, bool one_sided) {
  const MeanVariance m = mean_variance(log_ratios);
  const double n = double(log_ratios.size());
  MarginTest r;
  r.change = m.mean;
  const double excess = (one_sided ? m.mean : std::abs(m.mean)) - margin;
  if (!std::isfinite(m.mean)) {
    r.t = {NAN, 0.0};
  } else if (excess > 0.0) {
    const double se = std::sqrt(m.variance / n);
    r.t.t = se > 0.0 ? excess / se : INFINITY;
    const double upper = student_t_upper_p(r.t.t, n - 1.0);
    r.t.p = one_sided ? upper : std::min(1.0, 2.0 * upper);
  }
  return r;
}

// A mean as it enters a log ratio: values at or below `floor` (a small fraction of the image's
// mean) count as the floor, so that a block that turned black is a large finite change.
double log_above(double v, double floor) { return std::log(std::max(v, floor)); }

}  // namespace

nlohmann::json make_distribution_baseline(const nlohmann::json& results, const std::string& results_dir,
                                          const std::string& baseline_dir, const DistributionParams& params) {
  if (params.block < 1) throw Error("check statistics: block must be >= 1");
  nlohmann::json out = {{"schema_version", 1}, {"block", params.block}, {"groups", nlohmann::json::array()}};
  std::set<std::string> stems;
  for (const GroupRuns& g : group_runs(results, results_dir)) {
    const int n = int(g.images.size());
    if (n < 2) throw Error("check statistics: group '" + g.group + "' has " + std::to_string(n) + " seed(s); at least 2 are needed");
    std::vector<Image> images;
    for (const std::string& path : g.images) images.push_back(read_image(path));
    const int w = images[0].width, h = images[0].height;
    Image mean(w, h), variance(w, h);
    for (const Image& im : images) {
      if (im.width != w || im.height != h) throw Error("check statistics: group '" + g.group + "' has images of different sizes");
      for (size_t i = 0; i < mean.data.size(); ++i) mean.data[i] += im.data[i] / float(n);
    }
    for (const Image& im : images)
      for (size_t i = 0; i < variance.data.size(); ++i)
        variance.data[i] += (im.data[i] - mean.data[i]) * (im.data[i] - mean.data[i]) / float(n - 1);
    // The energies are taken against the mean as stored (halves), as a check will take them.
    for (float& v : mean.data) v = glm::unpackHalf1x16(glm::packHalf1x16(std::clamp(v, -65504.0f, 65504.0f)));
    std::vector<Reduction> reductions;
    std::vector<double> energies;
    // A seed's difference from the mean of the other seeds is n / (n - 1) times its difference from
    // the mean of all, so the energy is scaled by the square of that.
    const double scale = (double(n) / (n - 1)) * (double(n) / (n - 1));
    for (const Image& im : images) {
      reductions.push_back(reduce(im, params.block));
      energies.push_back(log_energy(im, mean, scale));
    }
    const size_t values = reductions[0].blocks.size();
    std::vector<double> block_mean(values), block_variance(values);
    for (size_t k = 0; k < values; ++k) {
      const MeanVariance m = over_seeds(reductions, [k](const Reduction& r) { return r.blocks[k]; });
      block_mean[k] = m.mean, block_variance[k] = m.variance;
    }
    std::vector<double> image_mean(kChannels), image_variance(kChannels);
    for (int c = 0; c < kChannels; ++c) {
      const MeanVariance m = over_seeds(reductions, [c](const Reduction& r) { return r.image[c]; });
      image_mean[c] = m.mean, image_variance[c] = m.variance;
    }
    const MeanVariance e = mean_variance(energies);
    const MeanVariance noise = over_seeds(reductions, [](const Reduction& r) { return r.log_noise; });
    std::string stem = file_stem(g.group);
    for (int k = 2; stems.count(stem); ++k) stem = file_stem(g.group) + "-" + std::to_string(k);
    stems.insert(stem);
    const std::string file = "statistics/" + stem + ".exr";
    write_image((fs::path(baseline_dir) / file).string(), mean, {Layer{"variance", variance}}, 0.0f, ExrValues::float16);
    out["groups"].push_back({{"group", g.group},
                             {"method", g.method},
                             {"seeds", n},
                             {"width", w},
                             {"height", h},
                             {"images", file},
                             {"image_mean", image_mean},
                             {"image_variance", image_variance},
                             {"log_energy_mean", e.mean},
                             {"log_energy_variance", e.variance},
                             {"log_noise_mean", noise.mean},
                             {"log_noise_variance", noise.variance},
                             {"block_mean", to_floats(block_mean)},
                             {"block_variance", to_floats(block_variance)}});
  }
  return out;
}

void add_same_seed_records(nlohmann::json& statistics, const nlohmann::json& results, const std::string& results_dir,
                           const std::string& baseline_dir) {
  const int block = whole_number(statistics, "block", 1, 4096);
  std::map<std::string, GroupRuns> runs;
  for (GroupRuns& g : group_runs(results, results_dir)) runs[g.group] = std::move(g);
  for (nlohmann::json& b : statistics.at("groups")) {
    const std::string name = b.value("group", "");
    auto it = runs.find(name);
    if (it == runs.end()) continue;
    const Image base_mean = read_image((fs::path(baseline_dir) / b.value("images", "")).string());
    nlohmann::json records = nlohmann::json::array();
    for (size_t s = 0; s < it->second.images.size(); ++s) {
      if (!std::isfinite(it->second.seeds[s])) continue;
      const Image im = read_image(it->second.images[s]);
      if (im.width != base_mean.width || im.height != base_mean.height || !all_finite(im))
        throw Error("same-seed records of group '" + name + "': " + it->second.images[s] +
                    " is not a finite image of the statistics' size");
      records.push_back(same_seed_record(it->second.seeds[s], reduce(im, block), log_energy(im, base_mean, 1.0)));
    }
    b["same_seeds"] = records;
  }
}

DistributionOutcome check_distribution(const nlohmann::json& fresh, const std::string& fresh_dir,
                                       const nlohmann::json& statistics, const std::string& baseline_dir,
                                       const DistributionParams& p) {
  DistributionOutcome out;
  const int block = whole_number(statistics, "block", 1, 4096);
  std::map<std::string, GroupRuns> fresh_groups;
  for (GroupRuns& g : group_runs(fresh, fresh_dir)) fresh_groups[g.group] = std::move(g);

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
    MarginTest same_worst;      // the value with the smallest p
    std::string same_worst_what;
    std::vector<double> same_whole_p, same_block_p;
  };
  std::vector<Row> rows;
  // Pairs each fresh seed with the baseline's record of that seed and tests the log ratios of the
  // image means, the block means, the error energies and the pixel noise (margin_t).
  auto same_seed_tests = [&p](Row& row, const GroupRuns& g, const std::vector<Reduction>& fresh,
                              const std::vector<double>& energies, const std::vector<SameSeedRecord>& base, int blocks_x) {
    std::vector<std::pair<const Reduction*, const Reduction*>> pairs;  // fresh, baseline
    std::vector<double> energy_ratios, noise_ratios;
    for (size_t s = 0; s < fresh.size(); ++s)
      for (const SameSeedRecord& r : base)
        if (r.seed == g.seeds[s]) {
          pairs.push_back({&fresh[s], &r.reduction});
          energy_ratios.push_back(energies[s] - r.log_energy);
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
  };
  for (const nlohmann::json& b : member(statistics, "groups")) {
    Row row;
    row.group = b.value("group", "");
    row.method = b.value("method", "");
    const int n_base = whole_number(b, "seeds", 2, 1 << 20);
    const int w = whole_number(b, "width", 1, 1 << 16), h = whole_number(b, "height", 1, 1 << 16);
    row.seeds_base = n_base;
    const size_t blocks = size_t(blocks_across(w, block)) * blocks_across(h, block);
    out.whole_image_tests += kChannels + 1;
    out.block_tests += int(blocks) * kChannels;
    auto it = fresh_groups.find(row.group);
    if (it == fresh_groups.end()) {
      row.problem = "missing from the fresh results";
      row.missing = true;
      rows.push_back(row);
      continue;
    }
    const GroupRuns& g = it->second;
    row.seeds_fresh = int(g.images.size());
    if (row.seeds_fresh < 1) {
      row.problem = "no fresh seeds";
      rows.push_back(row);
      continue;
    }
    const std::string images = (fs::path(baseline_dir) / b.value("images", "")).string();
    const Image base_mean = read_image(images);
    const Image base_variance = read_layer(images, "variance");
    const std::vector<double> block_mean = doubles(b, row.group, "block_mean", blocks * kChannels);
    const std::vector<double> block_variance = doubles(b, row.group, "block_variance", blocks * kChannels);
    const std::vector<double> image_mean = doubles(b, row.group, "image_mean", kChannels);
    const std::vector<double> image_variance = doubles(b, row.group, "image_variance", kChannels);
    const bool injected = p.inject_method.empty() || p.inject_method == g.method;
    std::vector<Reduction> reductions;
    std::vector<double> energies;
    for (size_t s = 0; s < g.images.size(); ++s) {
      Image im = read_image(g.images[s]);
      if (im.width != w || im.height != h) {
        row.problem = "fresh images are " + std::to_string(im.width) + "x" + std::to_string(im.height) + ", the baseline's " +
                      std::to_string(w) + "x" + std::to_string(h);
        break;
      }
      if (!all_finite(im)) {
        row.problem = "non-finite values in " + g.images[s];
        break;
      }
      if (injected) inject(im, g.images[s], base_variance, p, Hash64().add(row.group).value() + s);
      reductions.push_back(reduce(im, block));
      energies.push_back(log_energy(im, base_mean, 1.0));
      if (std::isfinite(g.seeds[s]))
        out.same_seeds[row.group].push_back(same_seed_record(g.seeds[s], reductions.back(), energies.back()));
    }
    if (!row.problem.empty()) {
      rows.push_back(row);
      continue;
    }
    const int n = row.seeds_fresh;
    for (int c = 0; c < kChannels; ++c) {
      const MeanVariance fresh_mean = over_seeds(reductions, [c](const Reduction& r) { return r.image[c]; });
      const TTest t = pooled_t({image_mean[c], image_variance[c]}, n_base, fresh_mean, n, false);
      if (c == 0 || t.p < row.image.p) row.image = t, row.image_channel = c;
    }
    for (size_t k = 0; k < blocks * kChannels; ++k) {
      const MeanVariance fresh_mean = over_seeds(reductions, [k](const Reduction& r) { return r.blocks[k]; });
      const TTest t = pooled_t({block_mean[k], block_variance[k]}, n_base, fresh_mean, n, false);
      row.block_p.push_back(t.p);
      if (k == 0 || t.p < row.worst_block.p) row.worst_block = t;
    }
    const MeanVariance e_base{number(b, "log_energy_mean"), number(b, "log_energy_variance")};
    const MeanVariance e_fresh = mean_variance(energies);
    row.energy = pooled_t(e_base, n_base, e_fresh, n, true);
    row.energy_lower = {row.energy.t, student_t_upper_p(-row.energy.t, double(n_base + n - 2))};
    row.energy_ratio = std::exp(e_fresh.mean - e_base.mean);
    // Baselines made before the pixel-noise statistics have none to test against.
    const MeanVariance noise_base{number(b, "log_noise_mean"), number(b, "log_noise_variance")};
    if (std::isfinite(noise_base.mean) && std::isfinite(noise_base.variance)) {
      const MeanVariance noise_fresh = over_seeds(reductions, [](const Reduction& r) { return r.log_noise; });
      row.noise = pooled_t(noise_base, n_base, noise_fresh, n, true);
      row.noise_ratio = std::exp(noise_fresh.mean - noise_base.mean);
      out.whole_image_tests += 1;
    }
    same_seed_tests(row, g, reductions, energies, same_seed_records(b, row.group, blocks * kChannels),
                    blocks_across(w, block));
    out.whole_image_tests += int(row.same_whole_p.size());
    out.block_tests += int(row.same_block_p.size());
    rows.push_back(row);
  }

  // Half of alpha for the tests of whole images (the most powerful against a uniform bias or a rise
  // in variance), half for the many block tests.
  out.whole_image_threshold = 0.5 * p.alpha / std::max(out.whole_image_tests, 1);
  out.block_threshold = 0.5 * p.alpha / std::max(out.block_tests, 1);
  std::ostringstream t;
  t << "| group | seeds (baseline, fresh) | image mean: t (p) | blocks: largest abs t (p), failing | "
       "error energy: fresh / baseline (p) | pixel noise: fresh / baseline (p) | "
       "same seeds: n, largest change, t (p), failing | status |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  for (const Row& row : rows) {
    nlohmann::json g = {{"group", row.group}, {"method", row.method}, {"seeds_baseline", row.seeds_base},
                        {"seeds_fresh", row.seeds_fresh}};
    if (!row.problem.empty()) {
      g["status"] = row.missing ? "missing" : "fails";
      g["problem"] = row.problem;
      out.groups.push_back(g);
      t << "| " << row.group << " | " << row.seeds_base << ", " << row.seeds_fresh << " | - | - | - | - | - | FAILS: "
        << row.problem << " |\n";
      ++out.failures;
      continue;
    }
    const int failing_blocks = int(std::count_if(row.block_p.begin(), row.block_p.end(),
                                                 [&](double q) { return !(q >= out.block_threshold); }));
    auto below = [](const std::vector<double>& ps, double threshold) {
      return int(std::count_if(ps.begin(), ps.end(), [&](double q) { return !(q >= threshold); }));
    };
    const int same_failing =
        below(row.same_whole_p, out.whole_image_threshold) + below(row.same_block_p, out.block_threshold);
    const bool fails = !(row.image.p >= out.whole_image_threshold) || failing_blocks > 0 ||
                       !(row.energy.p >= out.whole_image_threshold) || !(row.noise.p >= out.whole_image_threshold) ||
                       same_failing > 0;
    const bool better = !fails && row.energy_lower.p < out.whole_image_threshold;
    const char channel = "RGB"[row.image_channel];
    t << "| " << row.group << " | " << row.seeds_base << ", " << row.seeds_fresh << " | " << channel
      << " " << fmt("%+.2f", row.image.t) << " (" << fmt("%.2g", row.image.p) << ") | "
      << fmt("%.2f", std::abs(row.worst_block.t)) << " (" << fmt("%.2g", row.worst_block.p) << "), " << failing_blocks
      << " | " << fmt("%.3f", row.energy_ratio) << " (" << fmt("%.2g", row.energy.p) << ") | ";
    if (std::isfinite(row.noise_ratio))
      t << fmt("%.3f", row.noise_ratio) << " (" << fmt("%.2g", row.noise.p) << ") | ";
    else
      t << "- | ";
    if (row.same_worst_what.empty())
      t << row.same_n << ", -";
    else
      t << row.same_n << ", " << row.same_worst_what << " " << fmt("%+.2f%%", 100.0 * std::expm1(row.same_worst.change))
        << ", " << fmt("%.3g", row.same_worst.t.t) << " (" << fmt("%.2g", row.same_worst.t.p) << "), " << same_failing;
    t << " | " << (fails ? "FAILS" : better ? "better" : "ok") << " |\n";
    if (fails) ++out.failures;
    g["status"] = fails ? "fails" : better ? "better" : "ok";
    auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    g["image_t"] = finite_or_null(row.image.t);
    g["image_p"] = row.image.p;
    g["block_t"] = finite_or_null(std::abs(row.worst_block.t));
    g["block_p"] = row.worst_block.p;
    g["failing_blocks"] = failing_blocks;
    g["energy_ratio"] = finite_or_null(row.energy_ratio);
    g["energy_p"] = row.energy.p;
    g["noise_ratio"] = finite_or_null(row.noise_ratio);
    g["noise_p"] = row.noise.p;
    g["same_seeds"] = row.same_n;
    if (!row.same_worst_what.empty()) {
      g["same_seeds_largest"] = row.same_worst_what;
      g["same_seeds_change"] = finite_or_null(std::expm1(row.same_worst.change));
      g["same_seeds_t"] = finite_or_null(row.same_worst.t.t);
      g["same_seeds_p"] = row.same_worst.t.p;
      g["same_seeds_failing"] = same_failing;
    }
    out.groups.push_back(g);
  }
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
