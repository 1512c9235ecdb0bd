// sst-render: renders one image of a glTF scene (or the built-in Cornell box) with one method and
// writes the image (EXR with AOV layers, PNG or HDR) and a JSON record of everything in effect.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/cli_common.h"
#include "app/param_flags.h"
#include "core/pipeline/backend.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/render_record.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene_search.h"
#include "core/util/stage_timer.h"

namespace {

struct Args {
  std::string scene;
  std::vector<std::string> outputs;
  std::string json_path;
  std::vector<std::string> scene_dirs;
  int repeat = 1;
  bool quiet = false;
  bool list_methods = false;
  bool list_devices = false;
};

void print_methods() {
  for (const sst::MethodInfo& m : sst::method_registry()) {
    std::printf("%s: %s\n", m.name.c_str(), m.description.c_str());
    for (const sst::ParamInfo& p : m.params)
      std::printf("  --%-20s %-6s default %-8s %s\n", sst::to_flag(p.name).c_str(), p.type.c_str(),
                  p.default_value.dump().c_str(), p.help.c_str());
  }
}

// One line per Vulkan device with a compute queue, or one line saying why there is none.
void print_devices() {
  std::string reason;
  std::vector<sst::DeviceInfo> devices = sst::list_vulkan_devices(&reason);
  if (devices.empty()) std::printf("no Vulkan device: %s\n", reason.c_str());
  for (const sst::DeviceInfo& d : devices)
    std::printf("%d: %s (%s), Vulkan %s, max storage buffer %.0f MiB%s%s\n", d.index, d.name.c_str(), d.type.c_str(),
                sst::api_version_string(d.api_version).c_str(), double(d.max_storage_buffer_range) / (1024.0 * 1024.0),
                d.driver.empty() ? "" : ", driver ", d.driver.c_str());
}

// Splits the given flags into render options and the chosen method's parameters; a flag that
// belongs to neither (another method's parameter) is an error rather than silently ignored.
void split_flags(const nlohmann::json& given, sst::RenderOptions& options, nlohmann::json& method_params) {
  sst::params_from_json(options, given, "command line", true);
  const sst::MethodInfo& method = sst::find_method(options.method);
  auto common = sst::param_names<sst::RenderOptions>();
  method_params = nlohmann::json::object();
  for (const auto& [key, value] : given.items()) {
    if (std::find(common.begin(), common.end(), key) != common.end()) continue;
    bool known = std::any_of(method.params.begin(), method.params.end(), [&](const auto& p) { return p.name == key; });
    if (!known) throw sst::Error("--" + sst::to_flag(key) + " does not apply to method '" + options.method + "'");
    method_params[key] = value;
  }
}

sst::Scene load_scene(const Args& args) {
  if (args.scene.empty()) return sst::load_default_scene();
  return sst::load_gltf(sst::resolve_scene(args.scene, args.scene_dirs));
}

int run(const Args& args, const sst::app::ParamFlags& flags) {
  if (args.list_methods) {
    print_methods();
    return 0;
  }
  if (args.list_devices) {
    print_devices();
    return 0;
  }
  if (args.repeat < 1) throw sst::Error("--repeat must be >= 1");
  sst::RenderOptions options;
  nlohmann::json method_params;
  split_flags(flags.given(), options, method_params);
  sst::find_method(options.method);

  sst::StageTimer load_timer;
  sst::Scene scene = load_timer.time("load", [&] { return load_scene(args); });
  for (const std::string& w : scene.warnings)
    if (!args.quiet) std::fprintf(stderr, "warning: %s\n", w.c_str());

  std::vector<sst::RenderResult> runs;
  for (int i = 0; i < args.repeat; ++i) runs.push_back(sst::render_frame(scene, options, method_params, args.quiet));
  sst::RenderResult& last = runs.back();

  std::vector<std::string> outputs = args.outputs.empty() ? std::vector<std::string>{"render.exr"} : args.outputs;
  sst::StageTimer write_timer;
  write_timer.time("write", [&] {
    for (const std::string& path : outputs)
      sst::write_image(path, last.frame.color, last.frame.layers(), last.options.exposure);
  });

  std::string json_path = args.json_path.empty()
                              ? std::filesystem::path(outputs.front()).replace_extension(".json").string()
                              : args.json_path;
  nlohmann::json record = sst::make_render_record("sst-render", scene, runs, load_timer, write_timer);
  record["outputs"] = {{"images", outputs}, {"json", json_path}};
  sst::write_json_atomic(json_path, record);
  if (!args.quiet) {
    const auto& c = last.frame.counters;
    double ms = sst::frame_ms(last);
    std::fprintf(stderr, "%s: %dx%d, %d spp, %s on %s: frame %.1f ms, %.2f Mrays/s -> %s\n", options.method.c_str(),
                 last.options.width, last.options.height, last.options.spp, scene.source.c_str(),
                 last.device.value("name", std::string("?")).c_str(), ms,
                 c.to_json(ms)["mrays_per_s"].get<double>(), outputs.front().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sst-render: render one image of a glTF scene (no scene: the built-in Cornell box)"};
  Args args;
  sst::app::ParamFlags flags;
  app.add_option("scene", args.scene, "glTF scene (.gltf/.glb): a path, or a name found on the scene search path");
  app.add_option("-o,--output", args.outputs, "output image(s): .exr (with AOV layers), .png, .hdr [render.exr]");
  app.add_option("--json", args.json_path, "JSON record path [output path with .json]");
  app.add_option("--scene-dir", args.scene_dirs, "directory to search for scenes (repeatable; also SST_SCENE_PATH)");
  app.add_option("--repeat", args.repeat, "render this many times; timings are medians with min and max");
  app.add_flag("-q,--quiet", args.quiet, "no progress or summary on stderr");
  app.add_flag("--list-methods", args.list_methods, "list methods and their parameters");
  app.add_flag("--list-devices", args.list_devices, "list the Vulkan devices (for --backend vulkan) and exit");
  flags.add(app, sst::param_table<sst::RenderOptions>(), "Render options");
  for (const sst::MethodInfo& m : sst::method_registry()) flags.add(app, m.params, "Method '" + m.name + "'");
  CLI11_PARSE(app, argc, argv);
  return sst::app::run_guarded([&] { return run(args, flags); });
}
