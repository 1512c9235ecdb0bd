// `sst-eval table`: the groups of a results.json as a table like the papers' (one row per sweep
// point: time, RMSE, SSIM, gain), in Markdown or CSV.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sst {

// `stages`: extra columns with the median time of these stages ("sampling", "tree_build", ...).
// sst::Error for an unknown format.
std::string format_table(const nlohmann::json& results, const std::string& format,
                         const std::vector<std::string>& stages = {});

}  // namespace sst
