// `sst-eval merge`: joins the results of a sweep's shards (each rendered by `sweep --shard i/n`,
// possibly on other machines into other folders) into one results folder.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sst {

// Every folder must hold the same config (config.json); together they must hold every run of
// it, else sst::Error naming how many and which are missing. Run folders and reference images
// found elsewhere are copied into `output_dir`. Writes and returns results.json (and the CSV and
// report).
nlohmann::json merge_sweep(const std::vector<std::string>& shard_dirs, const std::string& output_dir);

}  // namespace sst
