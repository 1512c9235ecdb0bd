// Finding a scene by name: large scenes live outside the repository, in folders named by
// --scene-dir (repeatable) and the colon-separated environment variable SST_SCENE_PATH.
#pragma once
#include <string>
#include <vector>

namespace sst {

// The folders searched, in order: `scene_dirs` (from --scene-dir), then each non-empty entry of
// SST_SCENE_PATH. Recorded in the JSON output so that a run says where its scene came from.
std::vector<std::string> scene_search_dirs(const std::vector<std::string>& scene_dirs);

// An existing file is returned as given. Otherwise, in each search folder <dir>, the first
// existing file of: <dir>/<name>, <dir>/<name>.gltf, <dir>/<name>.glb,
// <dir>/<name>/<name>.gltf, <dir>/<name>/<name>.glb, and for every prefix <base> of the name
// that ends before a '-' (longest first), <dir>/<base>/<name>.gltf and .glb: so
// "staircase-point" finds <dir>/staircase/staircase-point.gltf and "cornell-box-point" finds
// <dir>/cornell-box/cornell-box-point.gltf. Not found: sst::Error listing the folders searched.
std::string resolve_scene(const std::string& name_or_path, const std::vector<std::string>& scene_dirs);

}  // namespace sst
