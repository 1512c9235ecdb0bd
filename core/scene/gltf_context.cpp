#include "core/scene/gltf_context.h"

#include <cmath>
#include <sstream>

#include "core/util/error.h"

namespace sst::gltf {

void Warnings::add(const std::string& message) {
  auto [it, fresh] = count_.try_emplace(message, 0);
  if (fresh) order_.push_back(message);
  ++it->second;
}

void Warnings::append_to(std::vector<std::string>& out) const {
  for (const std::string& m : order_) {
    size_t n = count_.at(m);
    out.push_back(n > 1 ? m + " (" + std::to_string(n) + " times)" : m);
  }
}

void Context::fail(const std::string& problem) const { throw Error(file + ": " + problem); }

std::string first_line(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    size_t e = line.find_last_not_of(" \t\r");
    return line.substr(b, e - b + 1);
  }
  return "unknown error";
}

const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key) {
  if (!object.IsObject() || !object.Has(key)) return nullptr;
  return &object.Get(key);
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const std::string& name) {
  auto it = extensions.find(name);
  return it == extensions.end() ? nullptr : &it->second;
}

double number_or(const tinygltf::Value* v, double fallback) {
  return v && v->IsNumber() ? v->GetNumberAsDouble() : fallback;
}

std::string quoted_name(const std::string& kind, size_t index, const std::string& name) {
  return kind + " " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
}

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace sst::gltf
