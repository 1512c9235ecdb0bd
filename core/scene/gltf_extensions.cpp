#include "core/scene/gltf_extensions.h"

#include <array>
#include <string>
#include <type_traits>

namespace sst::gltf {
namespace {

// Required extensions we accept: only what we implement or what cannot change the image.
struct AcceptedExtension {
  std::string_view name;
  std::string_view why;
};
constexpr std::array kAcceptedRequiredExtensions = {
    AcceptedExtension{"KHR_draco_mesh_compression", "implemented: decoded with Draco (core/scene/draco_mesh.h)"},
    AcceptedExtension{"KHR_lights_punctual", "implemented: point, spot and directional lights"},
    AcceptedExtension{"KHR_materials_emissive_strength", "implemented: scales emissiveFactor"},
    AcceptedExtension{"KHR_mesh_quantization", "implemented: integer POSITION/NORMAL/TEXCOORD_n"},
    AcceptedExtension{"KHR_texture_transform", "implemented: applied to the UVs (one per material)"},
    AcceptedExtension{"KHR_xmp_json_ld", "metadata only"},
};
// Extensions that are used, not required, and that we implement: no "ignored" warning.
constexpr std::array<std::string_view, 5> kImplementedExtensions = {
    "KHR_draco_mesh_compression", "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_mesh_quantization",
    "KHR_texture_transform"};

template <class Table>
bool contains(const Table& table, std::string_view name) {
  for (const auto& entry : table) {
    if constexpr (std::is_same_v<std::decay_t<decltype(entry)>, AcceptedExtension>) {
      if (entry.name == name) return true;
    } else if (entry == name) {
      return true;
    }
  }
  return false;
}

}  // namespace

void check_extensions(Context& ctx) {
  for (const std::string& name : ctx.model.extensionsRequired) {
    if (!contains(kAcceptedRequiredExtensions, name))
      ctx.fail("requires unsupported extension " + name);
  }
  for (const std::string& name : ctx.model.extensionsUsed) {
    if (name == "KHR_mesh_quantization") ctx.quantization = true;
    if (!contains(kImplementedExtensions, name))
      ctx.warnings.add("extension " + name + " is not supported: ignored");
  }
  if (contains(ctx.model.extensionsRequired, std::string_view("KHR_mesh_quantization"))) ctx.quantization = true;
}

bool implemented_extension(std::string_view name) { return contains(kImplementedExtensions, name); }

}  // namespace sst::gltf
