#include "core/scene/gltf_checks.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "core/util/error.h"
#include "core/util/json_io.h"

namespace sst::gltf {
namespace {

uint32_t little_endian32(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | uint8_t(bytes[at + size_t(i)]);
  return v;
}

}  // namespace

std::string_view checked_glb_json(std::string_view bytes, const std::string& name) {
  auto fail = [&](const std::string& problem) -> std::string_view { throw Error(name + ": invalid GLB: " + problem); };
  if (bytes.size() < 20) return fail("shorter than its 12-byte header and a chunk header");
  if (uint32_t version = little_endian32(bytes, 4); version != 2) return fail("version " + std::to_string(version) + " (glTF 2.0 is version 2)");
  if (uint32_t length = little_endian32(bytes, 8); length != bytes.size())
    return fail("header says " + std::to_string(length) + " bytes, the file has " + std::to_string(bytes.size()));
  uint64_t json_length = little_endian32(bytes, 12);
  if (little_endian32(bytes, 16) != 0x4E4F534Au) return fail("the first chunk is not JSON");
  if (json_length == 0 || 20 + json_length > bytes.size())
    return fail("JSON chunk of " + std::to_string(json_length) + " bytes in a file of " + std::to_string(bytes.size()));
  uint64_t at = 20 + json_length;
  while (at < bytes.size()) {  // the BIN chunk, and any later chunk (which readers must skip)
    if (bytes.size() - at < 8) return fail("truncated chunk header at byte " + std::to_string(at));
    uint64_t chunk_length = little_endian32(bytes, at);
    if (chunk_length > bytes.size() - at - 8)
      return fail("chunk at byte " + std::to_string(at) + " declares " + std::to_string(chunk_length) + " bytes, " +
                  std::to_string(bytes.size() - at - 8) + " follow");
    at += 8 + chunk_length;
  }
  return bytes.substr(20, json_length);
}

void check_gltf_json(std::string_view json_text, const std::string& name) {
  require_json_depth(json_text, name);
  nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return;  // tinygltf reports malformed JSON itself
  auto buffers = j.find("buffers");
  if (buffers == j.end() || !buffers->is_array()) return;
  for (size_t i = 0; i < buffers->size(); ++i) {
    const nlohmann::json& b = (*buffers)[i];
    auto length = b.is_object() ? b.find("byteLength") : b.end();
    if (length != b.end() && length->is_number() && !(length->get<double>() >= 1.0))
      throw Error(name + ": buffer " + std::to_string(i) + " has byteLength " + length->dump() + " (glTF requires >= 1)");
  }
}

std::optional<std::string> without_draco_index_accessors(std::string_view json_text) {
  nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return std::nullopt;
  const nlohmann::json* accessors = j.contains("accessors") && j["accessors"].is_array() ? &j["accessors"] : nullptr;
  bool changed = false;
  for (nlohmann::json& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("indices") || !prim.contains("extensions") ||
          !prim["extensions"].is_object() || !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      const nlohmann::json& index = prim["indices"];
      const bool listed = accessors && index.is_number_unsigned() && index.get<uint64_t>() < accessors->size();
      if (listed && (*accessors)[index.get<size_t>()].is_object() && (*accessors)[index.get<size_t>()].contains("bufferView"))
        continue;
      prim.erase("indices");
      changed = true;
    }
  }
  if (!changed) return std::nullopt;
  return j.dump();
}

std::string glb_with_json(std::string_view glb, std::string_view old_json, std::string json_text) {
  while (json_text.size() % 4) json_text.push_back(' ');
  std::string out(glb.substr(0, 12));
  auto put32 = [&](uint32_t v, size_t at) { std::memcpy(out.data() + at, &v, 4); };
  const std::string_view rest = glb.substr(std::min(glb.size(), 20 + old_json.size()));
  out += std::string(8, '\0');
  put32(uint32_t(json_text.size()), 12);
  put32(0x4E4F534Au, 16);  // "JSON"
  out += json_text;
  out += rest;
  put32(uint32_t(out.size()), 8);
  return out;
}

}  // namespace sst::gltf
