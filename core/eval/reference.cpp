#include "core/eval/reference.h"

#include <cstdlib>
#include <filesystem>

#include "core/pipeline/method_registry.h"
#include "core/pipeline/render_record.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/util/error.h"
#include "core/util/hash.h"
#include "core/util/json_io.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

nlohmann::json shared_options(const RunSpec& run) {
  nlohmann::json o = {{"backend", "cpu"}};
  for (const char* key : {"width", "height", "camera", "diffuse_only"})
    if (run.options.contains(key)) o[key] = run.options[key];
  return o;
}

// The reference config's keys other than kind/spp/seed/light_sampler are parameters of `method`.
nlohmann::json method_overrides(const nlohmann::json& cfg, const std::string& method) {
  nlohmann::json params = nlohmann::json::object();
  const MethodInfo& info = find_method(method);
  for (const auto& [key, value] : cfg.items()) {
    if (key == "kind" || key == "spp" || key == "seed" || key == "light_sampler" || key == "mask") continue;
    bool known = std::any_of(info.params.begin(), info.params.end(),
                             [&name = key](const ParamInfo& p) { return p.name == name; });
    if (!known) throw Error("reference: '" + key + "' is not a parameter of its method '" + method + "'");
    params[key] = value;
  }
  return params;
}

void add_external_files(Hash64& hash, const fs::path& gltf) {
  nlohmann::json j = read_json_file(gltf.string());
  for (const char* list : {"buffers", "images"}) {
    if (!j.contains(list)) continue;
    for (const auto& item : j[list]) {
      std::string uri = item.value("uri", std::string());
      if (!uri.empty() && uri.rfind("data:", 0) != 0) hash.add(uri).add_file((gltf.parent_path() / uri).string());
    }
  }
}

}  // namespace

ReferenceSpec reference_for(const RunSpec& run, const nlohmann::json& cfg, const std::string& scene_content_hash) {
  ReferenceSpec r;
  r.kind = cfg.value("kind", std::string("path"));
  r.scene = run.scene;
  r.options = shared_options(run);
  if (r.kind == "path") {
    r.options["method"] = "pt";
    r.options["spp"] = cfg.value("spp", 1024);
    r.options["seed"] = cfg.value("seed", 1000003u);
    // Only when given, so that the identity (and the cache) of every other reference stays as it was.
    if (cfg.contains("light_sampler")) r.options["light_sampler"] = cfg["light_sampler"];
    r.method_params = {{"max_bounces", 8}};
    r.method_params.update(method_overrides(cfg, "pt"));
  } else if (r.kind == "vpl") {
    const MethodInfo& method = find_method(run.options["method"].get<std::string>());
    const MethodInfo& exhaustive = find_method("exhaustive");
    bool has_vpls = std::any_of(method.params.begin(), method.params.end(), [](const ParamInfo& p) { return p.name == "vpls"; });
    if (!has_vpls) throw Error("reference kind 'vpl' needs a VPL method, but run " + run.id + " uses '" + method.name + "'");
    if (cfg.contains("seed")) throw Error("reference: a 'vpl' reference uses the run's seed (its VPL set); drop 'seed'");
    r.options["method"] = "exhaustive";
    r.options["spp"] = cfg.value("spp", 64);
    r.options["seed"] = run.seed;
    r.method_params = nlohmann::json::object();
    for (const ParamInfo& p : exhaustive.params)
      if (p.name != "export_vpls" && run.method_params.contains(p.name)) r.method_params[p.name] = run.method_params[p.name];
    r.method_params.update(method_overrides(cfg, "exhaustive"));
  } else {
    throw Error("reference: unknown kind '" + r.kind + "' (path or vpl)");
  }
  create_method(r.options["method"].get<std::string>(), r.method_params);  // checks the values
  nlohmann::json identity = {{"version", kReferenceVersion}, {"kind", r.kind},       {"scene", scene_content_hash},
                             {"options", r.options},          {"method_params", r.method_params}};
  r.id = Hash64().add(identity.dump()).hex();
  return r;
}

ReferenceSpec emitter_mask_for(const ReferenceSpec& reference) {
  ReferenceSpec m;
  m.kind = "mask";
  m.scene = reference.scene;
  m.options = {{"backend", "cpu"}, {"method", "pt"}, {"spp", 64}, {"seed", 1000003u}, {"diffuse_only", true}};
  for (const char* key : {"width", "height", "camera"})
    if (reference.options.contains(key)) m.options[key] = reference.options[key];
  m.method_params = {{"max_bounces", 0}};
  nlohmann::json identity = {{"version", kReferenceVersion}, {"kind", m.kind}, {"of", reference.id},
                             {"options", m.options}, {"method_params", m.method_params}};
  m.id = Hash64().add(identity.dump()).hex();
  return m;
}

std::string scene_content_hash(const std::string& scene_path) {
  Hash64 hash;
  if (scene_path.empty()) return hash.add(embedded_file("cornell-box.gltf")).hex();
  hash.add_file(scene_path);
  if (fs::path(scene_path).extension() == ".gltf") add_external_files(hash, scene_path);
  return hash.hex();
}

std::string default_reference_cache_dir() {
  if (const char* dir = std::getenv("SST_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "sst/references").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache/sst/references").string();
  return ".sst-cache/references";
}

ReferenceCache::ReferenceCache(std::string dir) : dir_(dir.empty() ? default_reference_cache_dir() : std::move(dir)) {}

Image ReferenceCache::get(const ReferenceSpec& spec, const Scene& scene, bool quiet, nlohmann::json* record) {
  fs::path exr = fs::path(dir_) / (spec.id + ".exr");
  fs::path json = fs::path(dir_) / (spec.id + ".json");
  if (fs::exists(exr) && fs::exists(json)) {
    if (record) *record = read_json_file(json.string());
    return read_image(exr.string());
  }
  if (!quiet) std::fprintf(stderr, "reference %s: %s %s, %d spp\n", spec.id.c_str(), spec.kind.c_str(),
                           scene.source.c_str(), spec.options["spp"].get<int>());
  RenderOptions options;
  params_from_json(options, spec.options, "reference " + spec.id);
  std::vector<RenderResult> runs = {render_frame(scene, options, spec.method_params, quiet)};
  write_image(exr.string(), runs.front().frame.color);
  nlohmann::json r = make_render_record("sst-eval", scene, runs, StageTimer(), StageTimer());
  r["reference"] = {{"id", spec.id}, {"kind", spec.kind}};
  write_json_atomic(json.string(), r);  // last: its presence means the EXR is complete
  if (record) *record = r;
  return runs.front().frame.color;
}

}  // namespace sst
