// The glTF extensions the loader accepts. glTF obliges a loader to refuse a file that requires an
// extension it does not implement, so the table of accepted ones is the loader's contract with
// the files it reads; it is kept apart so that supporting an extension edits one table.
#pragma once
#include <string_view>

#include "core/scene/gltf_context.h"

namespace sst::gltf {

// Refuses a file that requires an extension outside the accepted table, warns about each used
// extension that is not implemented, and sets ctx.quantization for KHR_mesh_quantization.
void check_extensions(Context& ctx);

// Whether the loader implements `name`: a file that uses it gets no "ignored" warning.
bool implemented_extension(std::string_view name);

}  // namespace sst::gltf
