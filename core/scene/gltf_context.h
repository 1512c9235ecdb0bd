// What every part of the glTF conversion shares: the parsed model, the file that messages name,
// the warnings and the glTF features the file uses, and the small readers of tinygltf values they
// all call. The parts (accessors, nodes, animation, materials, textures and the loader that ties
// them together) live in files of their own; reporting through one Context keeps every error one
// line starting with the file, and the warnings in the order the conversion meets them.
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace sst::gltf {

// Each distinct message once, in order of first appearance, with a count when it repeats.
class Warnings {
 public:
  void add(const std::string& message);
  void append_to(std::vector<std::string>& out) const;

 private:
  std::vector<std::string> order_;
  std::unordered_map<std::string, size_t> count_;
};

struct Context {
  Context(const tinygltf::Model& model, const std::string& file) : model(model), file(file) {}

  const tinygltf::Model& model;
  const std::string& file;  // starts every error message
  Warnings warnings;
  std::set<std::string> uses;  // becomes Scene::gltf_features
  bool quantization = false;   // KHR_mesh_quantization: integer positions, normals, UVs and keys

  // Throws sst::Error "<file>: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;
};

// The first non-blank line of `text`, trimmed: tinygltf reports errors as several lines, sometimes
// with a nlohmann exception prefix, and a message should be one line.
std::string first_line(const std::string& text);

// object[key], or null when `object` is not an object or lacks the key.
const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key);
// The extension `name` of an ExtensionMap, or null.
const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const std::string& name);
double number_or(const tinygltf::Value* v, double fallback);

// "<kind> <index>", followed by " ('<name>')" when the name is not empty.
std::string quoted_name(const std::string& kind, size_t index, const std::string& name);
bool all_finite(const std::vector<double>& values);

}  // namespace sst::gltf
