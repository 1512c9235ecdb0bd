// A decoded texture, row 0 at the top (glTF's uv origin), sampled bilinearly with the glTF
// sampler's wrap modes and no mip-mapping, as the Cycles references do.
// 8-bit images stay 8-bit (4 bytes a texel, decoded to linear per fetch through a 256-entry
// table): four times less memory traffic than float texels, which is what texture lookups cost
// in large scenes. 16-bit images keep float texels.
#pragma once
#include <cstdint>
#include <vector>

#include "core/math/math.h"

namespace sst {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

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

}  // namespace sst
