// The built-in default scene, so that a first run needs nothing but the binary: the Cornell box
// of scenes/cornell-box.gltf (yocto-gl's `cornellbox` preset, the scene the Cycles references of
// the Cornell box were rendered from; docs/scenes.md has its credits), compiled into the binary.
#pragma once
#include <string_view>

#include "core/scene/scene.h"

namespace sst {

// Bytes of a file embedded at build time (cmake/embed.cmake); empty when none has that name.
std::string_view embedded_file(std::string_view name);

// Scene::source is "builtin:cornell-box".
Scene load_default_scene();

}  // namespace sst
