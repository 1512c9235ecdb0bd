// Small glTF files for the tests, built in code: JSON here, one binary buffer written beside it
// as a .bin (or embedded, or packed into a .glb), and what the tests check of loading them.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene/gltf_loader.h"
#include "core/util/error.h"

namespace sst::test {
using nlohmann::json;
namespace fs = std::filesystem;

constexpr int kByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;

class GltfBuilder {
 public:
  json doc = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  template <class T>
  int view(const std::vector<T>& values, int stride = 0) {
    while (bin.size() % 4) bin.push_back('\0');
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", values.size() * sizeof(T)}};
    if (stride) v["byteStride"] = stride;
    bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size()) - 1;
  }
  int accessor(int view_index, int component_type, size_t count, const std::string& type, size_t offset = 0,
               bool normalized = false) {
    json a = {{"bufferView", view_index}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (offset) a["byteOffset"] = offset;
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size()) - 1;
  }
  int vec3s(const std::vector<float>& xyz) { return accessor(view(xyz), kFloat, xyz.size() / 3, "VEC3"); }
  template <class T>
  int indices(const std::vector<T>& idx, int component_type) {
    return accessor(view(idx), component_type, idx.size(), "SCALAR");
  }
  int mesh(const json& primitive) {
    doc["meshes"].push_back({{"primitives", json::array({primitive})}});
    return int(doc["meshes"].size()) - 1;
  }
  int node(const json& n) {
    doc["nodes"].push_back(n);
    return int(doc["nodes"].size()) - 1;
  }
  void scene(const std::vector<int>& roots) {
    doc["scenes"] = json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }
  int material(const json& m) {
    doc["materials"].push_back(m);
    return int(doc["materials"].size()) - 1;
  }
  // A triangle in the z = 0 plane facing +Z, with normals.
  int triangle_mesh(int material = -1) {
    json prim = {{"attributes", {{"POSITION", vec3s({0, 0, 0, 1, 0, 0, 0, 1, 0})}, {"NORMAL", vec3s({0, 0, 1, 0, 0, 1, 0, 0, 1})}}}};
    if (material >= 0) prim["material"] = material;
    return mesh(prim);
  }
  fs::path write(const fs::path& dir, const std::string& name) {
    fs::path gltf = dir / (name + ".gltf");
    json d = doc;
    if (!bin.empty()) {
      std::ofstream(dir / (name + ".bin"), std::ios::binary) << bin;
      d["buffers"] = json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
    }
    std::ofstream(gltf) << d.dump(1);
    return gltf;
  }
  fs::path write_glb(const fs::path& dir, const std::string& name) {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = d.dump();
    while (text.size() % 4) text.push_back(' ');
    std::string payload = bin;
    while (payload.size() % 4) payload.push_back('\0');
    std::string out = "glTF";
    auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + payload.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);  // JSON
    out += text;
    u32(uint32_t(payload.size()));
    u32(0x004E4942);  // BIN
    out += payload;
    fs::path glb = dir / (name + ".glb");
    std::ofstream(glb, std::ios::binary) << out;
    return glb;
  }
};

// A PNG with uncompressed (stored) deflate blocks: enough for tiny test images without zlib.
// `pixels` are the raw samples, row by row, 16-bit ones big-endian as PNG stores them.
inline fs::path write_png(const fs::path& path, int width, int height, int bit_depth, int color_type,
                   const std::vector<uint8_t>& pixels) {
  auto crc32 = [](const std::string& data) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char byte : data) {
      c ^= byte;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  size_t row_bytes = pixels.size() / size_t(height);
  std::string raw;
  for (int y = 0; y < height; ++y) {
    raw.push_back('\0');  // filter: none
    raw.append(reinterpret_cast<const char*>(pixels.data()) + y * row_bytes, row_bytes);
  }
  uint32_t a = 1, b = 0;
  for (unsigned char byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  uint16_t len = uint16_t(raw.size());
  std::string z = {char(0x78), char(0x01), char(0x01), char(len & 0xFF), char(len >> 8), char(~len & 0xFF), char((~len >> 8) & 0xFF)};
  z += raw + be32((b << 16) | a);
  std::string ihdr = be32(uint32_t(width)) + be32(uint32_t(height)) + std::string{char(bit_depth), char(color_type), 0, 0, 0};
  std::ofstream(path, std::ios::binary) << "\x89PNG\r\n\x1a\n" + chunk("IHDR", ihdr) + chunk("IDAT", z) + chunk("IEND", "");
  return path;
}

// The message of the sst::Error that loading `path` throws ("" when it loads).
inline std::string load_error(const fs::path& path) {
  try {
    load_gltf(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline void expect_one_line_naming(const std::string& message, const fs::path& file, const std::string& problem) {
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

inline bool has_warning(const Scene& s, const std::string& fragment) {
  for (const std::string& w : s.warnings)
    if (w.find(fragment) != std::string::npos) return true;
  return false;
}

}  // namespace sst::test
