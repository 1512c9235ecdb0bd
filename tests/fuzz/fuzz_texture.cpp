// libFuzzer harness: bytes as an encoded texture (PNG or JPEG, by their magic; PNG otherwise),
// embedded in a one-triangle GLB whose material samples it, so the bytes take the loader's whole
// path: the header checks of core/scene/encoded_image.h, then stb_image. Every input must decode
// or be refused with sst::Error; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/scene/gltf_loader.h"
#include "core/util/error.h"

namespace {

void append_u32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

std::string glb_with_image(const uint8_t* image, size_t size) {
  const bool jpeg = size >= 2 && image[0] == 0xFF && image[1] == 0xD8;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float uvs[6] = {0, 0, 1, 0, 0, 1};
  std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
  bin.append(reinterpret_cast<const char*>(image), size);
  while (bin.size() % 4) bin.push_back('\0');
  std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
      R"("textures":[{"source":0}],"images":[{"bufferView":2,"mimeType":")" +
      std::string(jpeg ? "image/jpeg" : "image/png") + R"("}],)" + R"("buffers":[{"byteLength":)" +
      std::to_string(bin.size()) + R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},)" +
      R"({"buffer":0,"byteOffset":36,"byteLength":24},{"buffer":0,"byteOffset":60,"byteLength":)" +
      std::to_string(size > 0 ? size : 1) + R"(}],"accessors":[)" +
      R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)" +
      R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}]})";
  while (json.size() % 4) json.push_back(' ');
  std::string glb = "glTF";
  append_u32(glb, 2);
  append_u32(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  append_u32(glb, uint32_t(json.size()));
  glb += "JSON";
  glb += json;
  append_u32(glb, uint32_t(bin.size()));
  glb.append("BIN\0", 4);
  glb += bin;
  return glb;
}

}  // namespace

// libFuzzer's entry point; the unit tests compile this file under another name
// (tests/core/fuzz_corpus_test.cpp runs every seed through it).
#ifndef SST_FUZZ_ENTRY
#define SST_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif
extern "C" int SST_FUZZ_ENTRY(const uint8_t* data, size_t size) {
  std::string glb = glb_with_image(data, size);
  try {
    sst::load_gltf_from_memory(glb, "/nonexistent-sst-fuzz", "fuzz-texture.glb");
  } catch (const sst::Error&) {
  }
  return 0;
}
