// KHR_draco_mesh_compression: one primitive's compressed geometry decoded with Google's Draco
// library (Debian's libdraco-dev) into the glTF loader's plain arrays. tinygltf can decode Draco
// itself (TINYGLTF_ENABLE_DRACO), but without bounds checks on the indices it follows; the loader
// hands this decoder only bytes it has checked, and everything the decoder returns is checked
// here (attribute ids, component counts, indices against the point count).
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sst {

struct DracoAttributeRequest {
  int unique_id = -1;       // the extension's attributes[semantic]
  bool normalized = false;  // the glTF accessor's flag: integer values map to [0, 1] / [-1, 1]
};

struct DracoPrimitive {
  size_t points = 0;
  std::vector<uint32_t> indices;  // a triangle list, every index < points
  // Per glTF semantic (POSITION, NORMAL, TEXCOORD_0, ...): `components[semantic]` floats a point.
  std::map<std::string, std::vector<float>> attributes;
  std::map<std::string, int> components;
};

// Decodes a Draco mesh of `size` bytes with the attributes `requests` names; throws sst::Error
// starting with `what` when the bytes are not a Draco triangle mesh or lack a requested attribute.
DracoPrimitive decode_draco_primitive(const unsigned char* bytes, size_t size,
                                      const std::map<std::string, DracoAttributeRequest>& requests,
                                      const std::string& what);

}  // namespace sst
