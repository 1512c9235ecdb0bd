// Cameras and punctual lights moved along key frames given in an experiment config or a JSON file
// (`paths`), for scenes that have no animation of their own (the shared scenes are static):
//
//   [{"camera": "<name or index>", "keys": [{"time": 0, "eye": [x, y, z], "target": [x, y, z]}, ...]},
//    {"light": "<name or index>", "keys": [{"time": 0, "position": [x, y, z]}, ...]}]
//
// A camera key gives where the eye is (`eye`, or `translate`: an offset from the camera's place in
// the scene) and where it looks (`target`, `forward`, or `yaw_degrees`: a turn about the camera's
// up axis from its direction in the scene; none: as in the scene), and optionally `up`. A light key
// gives `position` or `translate`, and optionally `direction` (spot and directional lights).
// Between keys the values are interpolated linearly (directions normalised); before the first
// key and after the last they hold. Times are seconds and must increase from key to key.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sst {

struct KeyFramePath {
  struct Key {
    double time = 0.0;
    vec3 position{0.0f};  // camera eye or light position
    vec3 forward{0.0f, 0.0f, -1.0f};  // camera forward or light direction, unit
    vec3 up{0.0f, 1.0f, 0.0f};        // camera up, unit (unused for lights)
  };
  bool camera = true;  // else a punctual light
  int index = 0;       // into Scene::cameras or Scene::lights
  std::string name;    // as the config gave it
  std::vector<Key> keys;
};

// Resolves `paths` (the JSON above) against the scene as loaded; `where` names the source (a file
// and key) in errors: a camera or light that does not exist, a key without a time, times that do
// not increase, a malformed vector, two keys that give the same value two ways.
std::vector<KeyFramePath> parse_key_frame_paths(const nlohmann::json& paths, const Scene& scene,
                                                const std::string& where);

// Moves the paths' cameras and lights to their place at time t (seconds). Returns whether a
// light moved (lights are built into the renderer's light sampler; cameras are not).
bool apply_key_frame_paths(const std::vector<KeyFramePath>& paths, Scene& scene, double t);

}  // namespace sst
