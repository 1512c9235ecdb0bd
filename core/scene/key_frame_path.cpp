#include "core/scene/key_frame_path.h"

#include <cmath>

#include "core/util/error.h"

namespace sst {
namespace {

vec3 read_vec3(const nlohmann::json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw Error(what + " must be an array of 3 numbers");
  vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!j[k].is_number()) throw Error(what + " must be an array of 3 numbers");
    double d = j[k].get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 1e30) throw Error(what + " has a non-finite or huge component");
    v[k] = float(d);
  }
  return v;
}

vec3 read_direction(const nlohmann::json& j, const std::string& what) {
  vec3 v = read_vec3(j, what);
  float len = glm::length(v);
  if (!(len > 0.0f) || !std::isfinite(len)) throw Error(what + " must be a non-zero direction");
  return v / len;
}

// The one of `names` that `key` gives (or "" when none); two given is an error.
std::string which_of(const nlohmann::json& key, std::initializer_list<const char*> names, const std::string& what) {
  std::string found;
  for (const char* n : names) {
    if (!key.contains(n)) continue;
    if (!found.empty()) throw Error(what + " gives both '" + found + "' and '" + n + "'");
    found = n;
  }
  return found;
}

// `v` rotated by `degrees` about the unit axis `axis` (Rodrigues).
vec3 rotate(vec3 v, vec3 axis, double degrees) {
  double a = degrees * 3.14159265358979323846 / 180.0;
  glm::dvec3 k(axis), x(v);
  glm::dvec3 r = x * std::cos(a) + glm::cross(k, x) * std::sin(a) + k * glm::dot(k, x) * (1.0 - std::cos(a));
  return vec3(r);
}

vec3 orthonormal_up(vec3 forward, vec3 up, const std::string& what) {
  vec3 u = up - glm::dot(up, forward) * forward;
  float len = glm::length(u);
  if (!(len > 1e-6f)) throw Error(what + ": up is parallel to the view direction");
  return u / len;
}

// Where a key puts its camera or light: `absolute` (eye or position), `translate` from `rest`, or
// `rest` when the key gives neither.
vec3 read_place(const nlohmann::json& key, const char* absolute, vec3 rest, const std::string& what) {
  std::string place = which_of(key, {absolute, "translate"}, what);
  if (place == absolute) return read_vec3(key[absolute], what + "." + absolute);
  if (place == "translate") return rest + read_vec3(key["translate"], what + ".translate");
  return rest;
}

KeyFramePath::Key parse_key(const nlohmann::json& j, const KeyFramePath& path, const Scene& scene,
                            const std::string& what) {
  if (!j.is_object()) throw Error(what + " must be an object");
  static const std::vector<std::string> camera_fields{"time", "eye", "translate", "target", "forward", "yaw_degrees", "up"};
  static const std::vector<std::string> light_fields{"time", "position", "translate", "direction"};
  const auto& allowed = path.camera ? camera_fields : light_fields;
  for (const auto& [name, value] : j.items())
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      throw Error(what + " has unknown field '" + name + "'");
  if (!j.contains("time") || !j["time"].is_number() || !std::isfinite(j["time"].get<double>()))
    throw Error(what + " needs a finite number 'time' (seconds)");
  KeyFramePath::Key key;
  key.time = j["time"].get<double>();
  if (path.camera) {
    const Camera& rest = scene.cameras[size_t(path.index)];
    key.position = read_place(j, "eye", rest.eye, what);
    key.up = j.contains("up") ? read_direction(j["up"], what + ".up") : rest.up;
    std::string look = which_of(j, {"target", "forward", "yaw_degrees"}, what);
    if (look == "target") {
      key.forward = read_vec3(j["target"], what + ".target") - key.position;
      if (!(glm::length(key.forward) > 0.0f)) throw Error(what + ": target is at the eye");
      key.forward = glm::normalize(key.forward);
    } else if (look == "forward") {
      key.forward = read_direction(j["forward"], what + ".forward");
    } else if (look == "yaw_degrees") {
      if (!j["yaw_degrees"].is_number() || !std::isfinite(j["yaw_degrees"].get<double>()))
        throw Error(what + ".yaw_degrees must be a finite number");
      key.forward = glm::normalize(rotate(rest.forward, key.up, j["yaw_degrees"].get<double>()));
    } else {
      key.forward = rest.forward;
    }
    key.up = orthonormal_up(key.forward, key.up, what);
  } else {
    const PunctualLight& rest = scene.lights[size_t(path.index)];
    key.position = read_place(j, "position", rest.position, what);
    key.forward = j.contains("direction") ? read_direction(j["direction"], what + ".direction") : rest.direction;
  }
  return key;
}

// The key-frame value at t: linear between the two keys around t, held outside them.
KeyFramePath::Key interpolate(const std::vector<KeyFramePath::Key>& keys, double t) {
  if (t <= keys.front().time) return keys.front();
  if (t >= keys.back().time) return keys.back();
  size_t i = 1;
  while (keys[i].time < t) ++i;
  const KeyFramePath::Key &a = keys[i - 1], &b = keys[i];
  float s = float((t - a.time) / (b.time - a.time));
  KeyFramePath::Key k;
  k.time = t;
  k.position = a.position + (b.position - a.position) * s;
  vec3 f = a.forward + (b.forward - a.forward) * s;
  // Opposite directions have no midpoint: hold the earlier one until the later key.
  k.forward = glm::length(f) > 1e-6f ? glm::normalize(f) : a.forward;
  vec3 u = a.up + (b.up - a.up) * s;
  u -= glm::dot(u, k.forward) * k.forward;
  k.up = glm::length(u) > 1e-6f ? glm::normalize(u) : a.up;
  return k;
}

}  // namespace

std::vector<KeyFramePath> parse_key_frame_paths(const nlohmann::json& paths, const Scene& scene,
                                                const std::string& where) {
  if (paths.is_null()) return {};
  if (!paths.is_array()) throw Error(where + " must be an array of paths");
  std::vector<KeyFramePath> out;
  for (size_t p = 0; p < paths.size(); ++p) {
    const nlohmann::json& j = paths[p];
    std::string what = where + "[" + std::to_string(p) + "]";
    if (!j.is_object()) throw Error(what + " must be an object with 'camera' or 'light' and 'keys'");
    for (const auto& [name, value] : j.items())
      if (name != "camera" && name != "light" && name != "keys") throw Error(what + " has unknown field '" + name + "'");
    KeyFramePath path;
    path.camera = j.contains("camera");
    if (path.camera == j.contains("light")) throw Error(what + " must name exactly one of 'camera' and 'light'");
    const nlohmann::json& target = j[path.camera ? "camera" : "light"];
    if (!target.is_string()) throw Error(what + "." + (path.camera ? "camera" : "light") + " must be a name or index");
    path.name = target.get<std::string>();
    path.index = path.camera ? scene.find_camera(path.name) : scene.find_light(path.name);
    if (path.index < 0)
      throw Error(what + ": no " + (path.camera ? "camera" : "light") + " '" + path.name + "' in " + scene.source);
    if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
      throw Error(what + " needs a non-empty array 'keys'");
    for (size_t k = 0; k < j["keys"].size(); ++k) {
      std::string key_what = what + ".keys[" + std::to_string(k) + "]";
      path.keys.push_back(parse_key(j["keys"][k], path, scene, key_what));
      if (k > 0 && !(path.keys[k].time > path.keys[k - 1].time))
        throw Error(key_what + ": time " + std::to_string(path.keys[k].time) + " does not increase");
    }
    out.push_back(std::move(path));
  }
  return out;
}

bool apply_key_frame_paths(const std::vector<KeyFramePath>& paths, Scene& scene, double t) {
  bool lights_moved = false;
  for (const KeyFramePath& path : paths) {
    KeyFramePath::Key k = interpolate(path.keys, t);
    if (path.camera) {
      Camera& c = scene.cameras[size_t(path.index)];
      c.eye = k.position;
      c.forward = k.forward;
      c.up = k.up;
    } else {
      PunctualLight& l = scene.lights[size_t(path.index)];
      lights_moved = lights_moved || l.position != k.position || l.direction != k.forward;
      l.position = k.position;
      l.direction = k.forward;
    }
  }
  return lights_moved;
}

}  // namespace sst
