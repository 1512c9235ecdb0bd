// The built-in default scene, so that a first run needs nothing but the binary: the Cornell box
// of scenes/cornell-box.gltf (the same scene as the shared Cycles reference
// ../shared/scenes/cornell-box), compiled into the binary.
#pragma once
#include <string_view>

#include "core/scene/scene.h"

namespace sst {

// Bytes of a file embedded at build time (cmake/embed.cmake); empty when none has that name.
std::string_view embedded_file(std::string_view name);

// Scene::source is "builtin:cornell-box".
Scene load_default_scene();

}  // namespace sst
