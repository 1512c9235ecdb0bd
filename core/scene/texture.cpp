#include "core/scene/texture.h"

#include <cstring>

namespace sst {
namespace {

// The texels as bytes: 8-bit texels are one word each, float texels four.
const unsigned char* texel_bytes(const Texture& t) {
  return !t.texels.empty() ? reinterpret_cast<const unsigned char*>(t.texels.data())
                           : reinterpret_cast<const unsigned char*>(t.rgba8.data());
}

uint32_t texel_word(const unsigned char* bytes, uint32_t w) {
  uint32_t word;
  std::memcpy(&word, bytes + 4 * size_t(w), sizeof word);
  return word;
}

}  // namespace
}  // namespace sst

#define TEXTURE_CTX_PARAM const unsigned char *texels,
#define TEXTURE_CTX texels,
#define TEXTURE_WORD(t, w) ::sst::texel_word(texels, w)
#define TEXTURE_TABLE_WORD(i) ::sst::glsl::scene_texel_tables[i]
#include "core/scene/texture_sample.h"

namespace sst {

vec4 Texture::texel(size_t i) const { return texture_texel(texel_bytes(*this), texture_layout(*this), uint32_t(i)); }

vec4 Texture::sample(vec2 uv) const { return texture_sample(texel_bytes(*this), texture_layout(*this), uv); }

}  // namespace sst
