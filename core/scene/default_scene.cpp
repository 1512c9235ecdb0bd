#include "core/scene/default_scene.h"

#include "core/scene/gltf_loader.h"
#include "core/util/error.h"

namespace sst {

Scene load_default_scene() {
  std::string_view bytes = embedded_file("cornell-box.gltf");
  if (bytes.empty()) throw Error("builtin:cornell-box: the default scene is missing from this build");
  // The embedded file carries its buffer as a data URI, so no folder is needed to resolve it.
  Scene scene = load_gltf_from_memory(bytes, "", "builtin:cornell-box");
  scene.source = "builtin:cornell-box";
  return scene;
}

}  // namespace sst
