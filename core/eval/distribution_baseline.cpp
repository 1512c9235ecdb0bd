// The baseline of the distribution check: make_distribution_baseline and add_same_seed_records
// (declared in distribution_check.h), and the reading of what they write back (distribution_baseline.h).
#include "core/eval/distribution_baseline.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "core/eval/distribution_check.h"
#include "core/eval/json_fields.h"
#include "core/image/image.h"
#include "core/util/error.h"

namespace sst {
namespace distribution {
namespace fs = std::filesystem;
namespace {

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

}  // namespace

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

int whole_number(const nlohmann::json& j, const char* key, int lo, int hi) {
  const double v = number(j, key);
  if (!(v >= lo && v <= hi) || v != std::floor(v))
    throw Error(std::string("check statistics: '") + key + "' must be a whole number in " + std::to_string(lo) + ".." +
                std::to_string(hi));
  return int(v);
}

std::vector<double> doubles(const nlohmann::json& j, const std::string& group, const char* key, size_t size) {
  const nlohmann::json& a = member(j, key);
  if (!a.is_array() || a.size() != size)
    throw Error("check statistics of group '" + group + "': '" + key + "' must hold " + std::to_string(size) + " numbers");
  std::vector<double> out;
  for (const nlohmann::json& v : a) out.push_back(number(v));
  return out;
}

nlohmann::json same_seed_record(double seed, const Reduction& r, double log_energy) {
  return {{"seed", seed},
          {"image", std::vector<double>(r.image.begin(), r.image.end())},
          {"blocks", to_floats(r.blocks)},
          {"log_energy", log_energy},
          {"log_noise", r.log_noise}};
}

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

}  // namespace distribution

using namespace distribution;

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

}  // namespace sst
