// glTF 2.0 (.gltf / .glb) -> sst::Scene: one world-space triangle soup with materials, textures,
// KHR_lights_punctual lights and cameras.
//
// Policy for what a file contains:
// - Bad input throws sst::Error with one line "<file>: <problem>": missing file, malformed JSON,
//   missing or short buffers (every accessor is bounds-checked here, not trusted to tinygltf),
//   vertex indices out of range, NaN/Inf in POSITION/NORMAL/TEXCOORD_0, a required extension
//   not in the loader's accepted table, a missing or undecodable image that a material uses,
//   and a scene without any triangle.
// - Things we can render correctly without, or that we deliberately simplify, are warnings in
//   Scene::warnings (each distinct message once, with a count): skipped POINTS/LINES
//   primitives, dropped zero-area triangles, generated flat normals, ignored alpha, normal and
//   occlusion textures, texCoord sets other than 0, KHR_texture_transform (when merely used),
//   light `range`, orthographic cameras, a generated "auto" camera.
// - A scene with no light at all (no punctual light, no emissive triangle) is NOT an error: it
//   loads with the warning "scene has no lights: the image will be black", because such a file
//   is valid glTF and a black image is then the right answer (and geometry-only files are
//   useful for AOV and timing runs).
#pragma once
#include <string>
#include <string_view>

#include "core/scene/scene.h"

namespace sst {

// Loads a file; .glb is recognised by its "glTF" magic, anything else is parsed as JSON.
// Scene::source is `path`.
Scene load_gltf(const std::string& path);

// Loads a glTF held in memory (JSON text or GLB bytes). External URIs resolve against
// `base_dir`; `name` identifies the file in messages and becomes Scene::source.
Scene load_gltf_from_memory(std::string_view bytes, const std::string& base_dir, const std::string& name);

}  // namespace sst
