// glTF 2.0 (.gltf / .glb) -> sst::Scene: one world-space triangle soup with materials, textures,
// KHR_lights_punctual lights and cameras, in the rest pose (the nodes' own transforms), and the
// file's animations as Scene::animation (core/scene/animation.h), which poses it at a time.
//
// Policy for what a file contains:
// - Bad input throws sst::Error with one line "<file>: <problem>": missing file, malformed JSON,
//   missing or short buffers (every accessor is bounds-checked here, not trusted to tinygltf),
//   vertex indices out of range, NaN/Inf in POSITION/NORMAL/TEXCOORD_0, a required extension
//   not in the loader's accepted table, a missing or undecodable image that a material uses,
//   a scene without any triangle, and broken animations: a missing sampler, accessor or node, key
//   times that are not finite and strictly increasing, an output count that does not match the
//   keys (x3 for CUBICSPLINE), an unknown interpolation or target path, an accessor of the wrong
//   type, a channel on a node with a matrix, two channels of one animation on one target.
// - Animations: node translation/rotation/scale channels with STEP, LINEAR and CUBICSPLINE keys
//   move rigid meshes, cameras and lights. All animations play at once on one clock; a target
//   two animations animate follows the later one (a warning names both).
// - Things we can render correctly without, or that we deliberately simplify, are warnings in
//   Scene::warnings (each distinct message once, with a count): skipped POINTS/LINES
//   primitives, dropped zero-area triangles, generated flat normals, ignored alpha, normal and
//   occlusion textures, textures of one material with different UV sets or KHR_texture_transforms
//   (the baseColorTexture's applies to all: the transform is applied to the vertices' UVs, one per
//   material), light `range`, orthographic cameras, a generated "auto" camera, skins (the rest pose is
//   rendered), morph targets and channels animating their weights (the base shape is rendered).
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
