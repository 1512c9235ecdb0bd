#include "core/eval/experiment_config.h"

#include <algorithm>
#include <filesystem>

#include "core/eval/reference.h"
#include "core/pipeline/method_registry.h"
#include "core/render/render_options.h"
#include "core/util/error.h"
#include "core/util/hash.h"
#include "core/util/json_io.h"
#include "core/util/params.h"

namespace sst {
namespace {

const std::vector<std::string> kConfigKeys = {"name",   "description",    "scenes",        "scene", "base",
                                              "axes",   "variants",       "reference",     "seeds", "repeat",
                                              "time_budget_ms", "warmup_frames", "paths",
                                              "metrics_layer"};

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void check_parameter_keys(const nlohmann::json& params, const std::string& context) {
  if (!params.is_object()) throw Error(context + ": expected an object of parameters");
  auto names = all_parameter_names();
  for (const auto& [key, value] : params.items())
    if (!contains(names, key))
      throw Error(context + ": unknown parameter '" + key + "' (did you mean '" + nearest_name(key, names) + "'?)");
}

// The reference's own keys, checked where the file is known (its method parameters are checked
// by reference_for, for each run).
void check_reference_values(const nlohmann::json& reference, const std::string& context) {
  if (reference.contains("kind") && !reference["kind"].is_string())
    throw Error(context + ": 'kind' must be \"path\" or \"vpl\", got " + reference["kind"].dump());
  if (reference.contains("spp") && !(fits<int>(reference["spp"]) && reference["spp"].get<int>() >= 1))
    throw Error(context + ": 'spp' must be an integer >= 1, got " + reference["spp"].dump());
  if (reference.contains("seed") && !fits<uint32_t>(reference["seed"]))
    throw Error(context + ": 'seed' must be an integer in 0..4294967295, got " + reference["seed"].dump());
}

int positive_int(const nlohmann::json& j, const std::string& context) {
  if (!j.is_number_integer() || j.get<long long>() < 1 || j.get<long long>() > 1000000)
    throw Error(context + ": expected a positive integer, got " + j.dump());
  return j.get<int>();
}

void parse_scenes(ExperimentConfig& c, const nlohmann::json& j, const std::string& context) {
  if (j.contains("scene") && j.contains("scenes")) throw Error(context + ": give 'scene' or 'scenes', not both");
  if (j.contains("scene")) {
    if (!j["scene"].is_string()) throw Error(context + ": 'scene' must be a string");
    c.scenes = {j["scene"].get<std::string>()};
  } else if (j.contains("scenes")) {
    if (!j["scenes"].is_array() || j["scenes"].empty()) throw Error(context + ": 'scenes' must be a non-empty list");
    for (const auto& s : j["scenes"]) {
      if (!s.is_string()) throw Error(context + ": 'scenes' must hold strings, got " + s.dump());
      c.scenes.push_back(s.get<std::string>());
    }
  } else {
    c.scenes = {""};  // the built-in Cornell box
  }
}

void parse_axes(ExperimentConfig& c, const nlohmann::json& axes, const std::string& context) {
  if (!axes.is_object()) throw Error(context + ": 'axes' must be an object {parameter: [values]}");
  check_parameter_keys(axes, context + ": axes");
  // nlohmann::json sorts object keys; the file's order is recovered from the source text
  // only through ordered_json, so axes are ordered by name: deterministic, and documented.
  for (const auto& [key, values] : axes.items()) {
    if (!values.is_array() || values.empty())
      throw Error(context + ": axis '" + key + "' must be a non-empty list of values");
    c.axes.emplace_back(key, std::vector<nlohmann::json>(values.begin(), values.end()));
  }
}

void parse_variants(ExperimentConfig& c, const nlohmann::json& variants, const std::string& context) {
  if (!variants.is_array()) throw Error(context + ": 'variants' must be a list of {name, params}");
  for (const auto& v : variants) {
    if (!v.is_object() || !v.contains("name") || !v["name"].is_string())
      throw Error(context + ": each variant needs a string 'name', got " + v.dump());
    for (const auto& [key, value] : v.items())
      if (key != "name" && key != "params")
        throw Error(context + ": variant '" + v["name"].get<std::string>() + "': unknown key '" + key +
                    "' (a variant has 'name' and 'params')");
    ExperimentVariant variant{v["name"].get<std::string>(), v.value("params", nlohmann::json::object())};
    check_parameter_keys(variant.params, context + ": variant '" + variant.name + "'");
    for (const auto& [axis, values] : c.axes)
      if (variant.params.contains(axis))
        throw Error(context + ": variant '" + variant.name + "' sets '" + axis + "', which is also a sweep axis");
    for (const ExperimentVariant& other : c.variants)
      if (other.name == variant.name) throw Error(context + ": two variants are named '" + variant.name + "'");
    c.variants.push_back(std::move(variant));
  }
}

std::string sanitize(const std::string& text) {
  std::string out;
  for (char ch : text) out += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.') ? ch : '_';
  return out;
}

std::string compact(const nlohmann::json& value) { return value.is_string() ? value.get<std::string>() : value.dump(); }

// Splits merged parameters into render options and the method's own parameters, dropping those
// that belong only to other methods, and checks every value.
void split_parameters(RunSpec& run, const nlohmann::json& merged, const std::string& context) {
  static const auto option_names = param_names<RenderOptions>();
  if (merged.contains("method") && !merged["method"].is_string())
    throw Error(context + ": 'method' must be a string, got " + merged["method"].dump());
  std::string method = merged.value("method", std::string("pt"));
  const MethodInfo& info = find_method(method);
  run.options = nlohmann::json::object();
  run.method_params = nlohmann::json::object();
  for (const auto& [key, value] : merged.items()) {
    if (key == "time_budget_ms") {
      if (!value.is_number() || value.get<double>() <= 0.0)
        throw Error(context + ": time_budget_ms must be a positive number, got " + value.dump());
      run.time_budget_ms = value.get<double>();
    } else if (contains(option_names, key)) {
      run.options[key] = value;
    } else if (std::any_of(info.params.begin(), info.params.end(),
                           [&name = key](const ParamInfo& p) { return p.name == name; })) {
      run.method_params[key] = value;
    }
  }
  run.options["method"] = method;
  try {
    RenderOptions options;
    params_from_json(options, run.options, "options");
    validate(options);
    create_method(method, run.method_params);  // throws on an impossible value
  } catch (const Error& e) {
    throw Error(context + ": " + e.what());
  }
}

}  // namespace

std::vector<std::string> all_parameter_names() {
  std::vector<std::string> names = param_names<RenderOptions>();
  for (const MethodInfo& m : method_registry())
    for (const ParamInfo& p : m.params)
      if (!contains(names, p.name)) names.push_back(p.name);
  names.push_back("time_budget_ms");
  return names;
}

ExperimentConfig parse_experiment_config(const nlohmann::json& j, const std::string& context) {
  if (!j.is_object()) throw Error(context + ": a config is a JSON object");
  ExperimentConfig c;
  c.source = j;
  auto parameter_names = all_parameter_names();
  std::vector<std::string> known = kConfigKeys;
  known.insert(known.end(), parameter_names.begin(), parameter_names.end());
  for (const auto& [key, value] : j.items()) {
    if (!contains(known, key))
      throw Error(context + ": unknown key '" + key + "' (did you mean '" + nearest_name(key, known) + "'?)");
    if (contains(parameter_names, key) && !contains(kConfigKeys, key)) c.base[key] = value;
  }
  for (const char* key : {"name", "description"})
    if (j.contains(key) && !j[key].is_string()) throw Error(context + ": '" + key + "' must be a string, got " + j[key].dump());
  c.name = j.value("name", std::string());
  c.description = j.value("description", std::string());
  parse_scenes(c, j, context);
  if (j.contains("base")) {
    check_parameter_keys(j["base"], context + ": base");
    for (const auto& [key, value] : j["base"].items()) {
      if (c.base.contains(key)) throw Error(context + ": '" + key + "' is given both at the top level and in base");
      c.base[key] = value;
    }
  }
  if (j.contains("time_budget_ms")) c.base["time_budget_ms"] = j["time_budget_ms"];
  if (j.contains("axes")) parse_axes(c, j["axes"], context);
  for (const auto& [axis, values] : c.axes)
    if (c.base.contains(axis)) throw Error(context + ": '" + axis + "' is both a sweep axis and a base parameter");
  if (j.contains("variants")) parse_variants(c, j["variants"], context);
  if (j.contains("reference")) {
    if (!j["reference"].is_object()) throw Error(context + ": 'reference' must be an object");
    check_reference_values(j["reference"], context + ": reference");
    c.reference = j["reference"];
  }
  if (j.contains("seeds")) c.seeds = positive_int(j["seeds"], context + ": seeds");
  if (j.contains("repeat")) c.repeat = positive_int(j["repeat"], context + ": repeat");
  if (j.contains("warmup_frames")) {
    const nlohmann::json& w = j["warmup_frames"];
    if (!w.is_number_integer() || w.get<long long>() < 0 || w.get<long long>() > 100000)
      throw Error(context + ": warmup_frames: expected an integer in 0..100000, got " + w.dump());
    c.warmup_frames = w.get<int>();
  }
  if (j.contains("metrics_layer")) {
    const nlohmann::json& m = j["metrics_layer"];
    if (!m.is_string() || (m != "color" && m != "direct" && m != "indirect"))
      throw Error(context + ": metrics_layer: expected \"color\", \"direct\" or \"indirect\", got " + m.dump());
    c.metrics_layer = m.get<std::string>();
  }
  if (j.contains("paths")) {
    if (!j["paths"].is_array()) throw Error(context + ": 'paths' must be a list of key-frame paths");
    c.paths = j["paths"];
  }
  return c;
}

ExperimentConfig load_experiment_config(const std::string& path) {
  ExperimentConfig c = parse_experiment_config(read_json_file(path), path);
  if (c.name.empty()) c.name = std::filesystem::path(path).stem().string();
  return c;
}

size_t count_runs(const ExperimentConfig& config) {
  // Saturating products: axes of a few values each multiply past 2^64 quickly.
  auto times = [](size_t a, size_t b) { return b != 0 && a > SIZE_MAX / b ? SIZE_MAX : a * b; };
  size_t runs = times(config.scenes.size(), std::max<size_t>(config.variants.size(), 1));
  for (const auto& axis : config.axes) runs = times(runs, axis.second.size());
  return times(runs, size_t(std::max(config.seeds, 1)));
}

std::vector<RunSpec> expand_runs(const ExperimentConfig& config) {
  // Every run is expanded and checked before anything renders, so their number is bounded first:
  // a config of a few lines can otherwise describe 1e8 runs and fill the memory before the first.
  if (size_t n = count_runs(config); n > kMaxRuns)
    throw Error("experiment '" + config.name + "' has " + (n == SIZE_MAX ? std::string("more than 2^64") : std::to_string(n)) +
                " runs (scenes x axes x variants x seeds); at most " + std::to_string(kMaxRuns) +
                " are allowed: split it into several configs");
  std::vector<RunSpec> runs;
  std::vector<ExperimentVariant> variants = config.variants;
  if (variants.empty()) variants.push_back({});
  size_t points = 1;
  for (const auto& axis : config.axes) points *= axis.second.size();
  for (const std::string& scene : config.scenes) {
    for (size_t point = 0; point < points; ++point) {
      nlohmann::json axes = nlohmann::json::object();
      for (size_t a = config.axes.size(), rest = point; a-- > 0;) {  // last axis varies fastest
        const auto& [key, values] = config.axes[a];
        axes[key] = values[rest % values.size()];
        rest /= values.size();
      }
      for (const ExperimentVariant& variant : variants) {
        nlohmann::json merged = config.base;
        merged.update(axes);
        merged.update(variant.params);
        uint32_t seed0 = 0;
        if (merged.contains("seed")) {
          // Checked before it is read: -1 would wrap to 4294967295, 1e39 does not fit at all.
          const nlohmann::json& seed = merged["seed"];
          if (!fits<uint32_t>(seed) || seed.get<uint64_t>() + uint64_t(config.seeds - 1) > UINT32_MAX)
            throw Error("experiment '" + config.name + "': seed must be an integer in 0..4294967295 (with the seeds after it), got " +
                        seed.dump());
          seed0 = seed.get<uint32_t>();
        }
        for (int s = 0; s < config.seeds; ++s) {
          RunSpec run;
          run.index = int(runs.size());
          run.scene = scene;
          run.variant = variant.name;
          run.axes = axes;
          run.repeat = config.repeat;
          run.warmup_frames = config.warmup_frames;
          run.metrics_layer = config.metrics_layer;
          run.paths = config.paths;
          nlohmann::json params = merged;
          run.seed = seed0 + uint32_t(s);
          params["seed"] = run.seed;
          std::string context = "run " + std::to_string(run.index) + (scene.empty() ? "" : " (" + scene + ")");
          split_parameters(run, params, context);
          std::string method = run.options["method"];
          run.label = variant.name.empty() ? method : axes.contains("method") ? variant.name + "/" + method : variant.name;
          char prefix[16];
          std::snprintf(prefix, sizeof prefix, "%04d-", run.index);
          run.id = prefix + sanitize(run.label);
          run.group = (config.scenes.size() > 1 ? (scene.empty() ? "default" : scene) + " " : "") + run.label;
          for (const auto& [key, value] : axes.items())  // the label already names the method
            if (key != "seed" && key != "method") run.group += " " + key + "=" + compact(value);
          nlohmann::json identity = {{"scene", scene},          {"options", run.options},
                                     {"method_params", run.method_params}, {"time_budget_ms", run.time_budget_ms},
                                     {"repeat", run.repeat}};
          // Only sequences name their frames, so the runs of earlier configs keep their hashes.
          if (run.warmup_frames > 0) identity["warmup_frames"] = run.warmup_frames;
          if (!run.paths.is_null()) identity["paths"] = run.paths;
          if (run.metrics_layer != "color") identity["metrics_layer"] = run.metrics_layer;
          run.spec_hash = Hash64().add(identity.dump()).hex();
          reference_for(run, config.reference, "");  // a bad reference fails now, not after hours
          runs.push_back(std::move(run));
        }
      }
    }
  }
  return runs;
}

}  // namespace sst
