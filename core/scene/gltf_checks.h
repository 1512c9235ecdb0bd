// A glTF file's bytes checked, and where needed rewritten, before tinygltf parses them: the GLB
// container's header and chunk lengths, and what in the JSON tinygltf would mishandle. These look
// at bytes and JSON text, not at a parsed model, so they are apart from the conversion, and each
// one stands for a known fault of the tinygltf that Debian ships.
#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace sst::gltf {

// The JSON chunk of a GLB, after checking its 12-byte header and the lengths of its chunks
// against the file. tinygltf 2.7 (Debian 12) compares the BIN chunk's length with the file
// without counting the chunk's 8-byte header, so a BIN chunk up to 8 bytes too long is read past
// the end of the buffer; nothing too long gets to it now. Throws sst::Error "<name>: invalid GLB: ...".
std::string_view checked_glb_json(std::string_view bytes, const std::string& name);

// What tinygltf would mishandle in the JSON itself: nesting deep enough to overflow its
// recursive conversion of extras/extensions, and an empty buffer, which it copies with
// vector::at(0) (glTF requires byteLength >= 1). Malformed JSON is left for tinygltf to report.
void check_gltf_json(std::string_view json_text, const std::string& name);

// tinygltf 2.8 refuses a primitive whose indices accessor has no bufferView, which is how
// KHR_draco_mesh_compression declares them (the indices are in the Draco data): such primitives
// lose their "indices" before tinygltf sees the JSON, and the loader takes them from Draco. The
// JSON text to hand tinygltf, when it changes.
std::optional<std::string> without_draco_index_accessors(std::string_view json_text);

// A GLB with its JSON chunk `old_json` replaced by `json_text` (the BIN chunk and anything after
// it kept).
std::string glb_with_json(std::string_view glb, std::string_view old_json, std::string json_text);

}  // namespace sst::gltf
