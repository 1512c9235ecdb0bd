// A decoded texture: linear float RGBA, row 0 at the top (glTF's uv origin), sampled bilinearly
// with the glTF sampler's wrap modes and no mip-mapping, as the Cycles references do.
#pragma once
#include <vector>

#include "core/math/math.h"

namespace sst {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<vec4> texels;  // linear (colour textures are sRGB-decoded at load)
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;
  bool nearest = false;  // glTF magFilter NEAREST

  vec4 sample(vec2 uv) const;
};

}  // namespace sst
