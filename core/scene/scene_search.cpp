#include "core/scene/scene_search.h"

#include <cstdlib>
#include <filesystem>

#include "core/util/error.h"

namespace sst {
namespace {
namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// Candidate paths inside one folder, most specific first.
std::vector<fs::path> candidates(const fs::path& dir, const std::string& name) {
  std::vector<fs::path> out = {dir / name, dir / (name + ".gltf"), dir / (name + ".glb"),
                               dir / name / (name + ".gltf"), dir / name / (name + ".glb")};
  for (size_t dash = name.rfind('-'); dash != std::string::npos && dash > 0; dash = name.rfind('-', dash - 1)) {
    fs::path folder = dir / name.substr(0, dash);
    out.push_back(folder / (name + ".gltf"));
    out.push_back(folder / (name + ".glb"));
  }
  return out;
}
}  // namespace

std::vector<std::string> scene_search_dirs(const std::vector<std::string>& scene_dirs) {
  std::vector<std::string> dirs;
  for (const std::string& d : scene_dirs)
    if (!d.empty()) dirs.push_back(d);
  if (const char* env = std::getenv("SST_SCENE_PATH")) {
    std::string path = env;
    size_t start = 0;
    while (start <= path.size()) {
      size_t colon = path.find(':', start);
      if (colon == std::string::npos) colon = path.size();
      if (colon > start) dirs.push_back(path.substr(start, colon - start));
      start = colon + 1;
    }
  }
  return dirs;
}

std::string resolve_scene(const std::string& name_or_path, const std::vector<std::string>& scene_dirs) {
  if (name_or_path.empty()) throw Error("empty scene name");
  if (is_file(name_or_path)) return name_or_path;
  std::vector<std::string> dirs = scene_search_dirs(scene_dirs);
  for (const std::string& dir : dirs)
    for (const fs::path& p : candidates(dir, name_or_path))
      if (is_file(p)) return p.string();
  if (dirs.empty())
    throw Error("scene '" + name_or_path + "' not found: no such file, and no scene folders to search (use --scene-dir or SST_SCENE_PATH)");
  std::string list;
  for (const std::string& d : dirs) list += (list.empty() ? "" : ", ") + d;
  throw Error("scene '" + name_or_path + "' not found: no such file, and not in the scene folders searched: " + list +
              " (--scene-dir, then SST_SCENE_PATH)");
}

}  // namespace sst
