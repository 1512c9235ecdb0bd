// glTF images decoded into sst Textures: the encoded bytes kept while tinygltf parses, checked
// (PNG or JPEG only, header sizes and a memory budget before anything is allocated), decoded in
// parallel, converted to RGBA per colour space, and given their sampler's wrap and filter. Apart
// from the materials (gltf_materials.h), which only say which (image, colour space, sampler)
// triples they use: decoding is the one part of loading that runs a third-party decoder on
// untrusted bytes, and the checks around it belong together.
#pragma once
#include <compare>
#include <string>
#include <vector>

#include "core/scene/gltf_accessors.h"
#include "core/scene/gltf_context.h"
#include "core/scene/texture.h"

namespace sst::gltf {

// One texture per (image, colour space, sampler) actually used.
struct TextureKey {
  int image;
  bool srgb;
  int sampler;
  auto operator<=>(const TextureKey&) const = default;
};

// tinygltf's image loader: keeps the encoded bytes instead of decoding, so that images decode in
// parallel and only when a material uses them (decode_textures). Images in bufferViews are re-read
// there with bounds checks, because tinygltf hands this callback a pointer it has not checked.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*);

// One texture per key, in order: the images the keys name decoded (stb via tinygltf) in parallel,
// each key's colour space applied, then its sampler. Fails for an image that is missing, not PNG
// or JPEG, larger than GPUs accept, beyond the memory budget or undecodable.
std::vector<Texture> decode_textures(Context& ctx, const Accessors& accessors, const std::vector<TextureKey>& keys);

}  // namespace sst::gltf
