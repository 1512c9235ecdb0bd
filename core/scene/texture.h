// A decoded texture, row 0 at the top (glTF's uv origin), sampled bilinearly with the glTF
// sampler's wrap modes and no mip-mapping, as the Cycles references do. The sampling itself is
// core/scene/texture_sample.h, shared with the GPU; it reads the texels where they are.
// 8-bit images stay 8-bit (4 bytes a texel, decoded to linear per fetch through a 256-entry
// table): four times less memory traffic than float texels, which is what texture lookups cost
// in large scenes. 16-bit images keep float texels.
#pragma once
#include <cstdint>
#include <vector>

#include "core/math/math.h"
#include "core/scene/scene_layout.h"

namespace sst {

// The glTF sampler's wrap modes, numbered as SCENE_WRAP_*.
enum class Wrap { Repeat = SCENE_WRAP_REPEAT, ClampToEdge = SCENE_WRAP_CLAMP_TO_EDGE, MirroredRepeat = SCENE_WRAP_MIRRORED_REPEAT };

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> rgba8;  // 8-bit texels, R in the low byte (empty for float textures)
  bool srgb = false;            // rgba8 colour channels are sRGB-encoded (alpha never is)
  std::vector<vec4> texels;     // float texels, linear (empty for 8-bit textures)
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;
  bool nearest = false;  // glTF magFilter NEAREST

  size_t texel_count() const { return size_t(width) * size_t(height); }
  vec4 texel(size_t i) const;  // linear RGBA of texel i
  vec4 sample(vec2 uv) const;
};

// The texture's size, format, wrap modes and filter as the shared sampling takes them
// (texel_offset 0: on the CPU the texels are the Texture's own; pack_scene sets the offset).
inline SceneTexture texture_layout(const Texture& t) {
  SceneTexture out;
  out.texel_offset = 0u;
  out.width = t.width > 0 ? t.width : 0;
  out.height = t.height > 0 ? t.height : 0;
  // Float texels win when both exist, as everywhere the texels are read.
  out.format = !t.texels.empty() ? SCENE_TEXTURE_RGBA32F : t.srgb ? SCENE_TEXTURE_RGBA8_SRGB : SCENE_TEXTURE_RGBA8;
  out.wrap_s = uint32_t(t.wrap_s);
  out.wrap_t = uint32_t(t.wrap_t);
  out.nearest = t.nearest ? 1u : 0u;
  out.reserved = 0u;
  return out;
}

}  // namespace sst
