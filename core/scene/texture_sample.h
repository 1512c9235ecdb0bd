// A texture's texels decoded to linear RGBA and sampled at a uv (sst::Texture: row 0 at the top,
// bilinear or nearest with the glTF sampler's wrap modes, no mip-mapping), in the common subset
// of C++ and GLSL (core/math/cpu_gpu.h): Texture::texel and Texture::sample on the CPU, the
// shaders' texture lookups on the GPU. The texture is described by its SceneTexture
// (core/scene/scene_layout.h: size, format, wrap modes, filter); its texels are read through
// hooks the includer defines before including this file:
//   TEXTURE_CTX_PARAM      a leading parameter with its trailing comma through which the hooks
//                          reach the texel data (C++: the texture's bytes), empty in GLSL
//   TEXTURE_CTX            the same as an argument
//   TEXTURE_WORD(t, w)     uint: word w of the texels of the texture t (a SceneTexture), counted
//                          from its first texel (the layout of SceneTexture.format)
//   TEXTURE_TABLE_WORD(i)  uint: word i of the 8-bit decoding tables (SCENE_TEXELS_SRGB_TABLE +
//                          c, SCENE_TEXELS_UNORM8_TABLE + c: SCENE_SRGB_DECODE_BITS and
//                          SCENE_UNORM8_BITS)
// The decoding tables hold the CPU's sRGB decode and c / 255 as float bits, so that both
// backends decode texels to the same floats without pow or division.
#ifndef SST_CORE_SCENE_TEXTURE_SAMPLE_H
#define SST_CORE_SCENE_TEXTURE_SAMPLE_H
#include "core/math/vector_math.h"
#include "core/scene/scene_layout.h"

#if !defined(TEXTURE_CTX_PARAM) || !defined(TEXTURE_CTX) || !defined(TEXTURE_WORD) || !defined(TEXTURE_TABLE_WORD)
#error "define the TEXTURE_* hooks before including core/scene/texture_sample.h"
#endif

SST_BEGIN

// glm::mix(x, y, a) = x * (1 - a) + y * a.
SST_FUNC vec4 texture_mix4(vec4 x, vec4 y, float a) {
  SST_PRECISE vec4 r = x * (1.0f - a) + y * a;
  return r;
}

// Linear RGBA of texel i (i counts texels, row-major).
SST_FUNC vec4 texture_texel(TEXTURE_CTX_PARAM SST_IN(SceneTexture) t, uint i) {
  if (t.format == SCENE_TEXTURE_RGBA32F) {
    uint o = 4u * i;
    return vec4(uintBitsToFloat(TEXTURE_WORD(t, o)), uintBitsToFloat(TEXTURE_WORD(t, o + 1u)),
                uintBitsToFloat(TEXTURE_WORD(t, o + 2u)), uintBitsToFloat(TEXTURE_WORD(t, o + 3u)));
  }
  uint v = TEXTURE_WORD(t, i);
  float a = uintBitsToFloat(TEXTURE_TABLE_WORD(SCENE_TEXELS_UNORM8_TABLE + (v >> 24u)));
  if (t.format == SCENE_TEXTURE_RGBA8_SRGB)
    return vec4(uintBitsToFloat(TEXTURE_TABLE_WORD(SCENE_TEXELS_SRGB_TABLE + (v & 0xFFu))),
                uintBitsToFloat(TEXTURE_TABLE_WORD(SCENE_TEXELS_SRGB_TABLE + ((v >> 8u) & 0xFFu))),
                uintBitsToFloat(TEXTURE_TABLE_WORD(SCENE_TEXELS_SRGB_TABLE + ((v >> 16u) & 0xFFu))), a);
  float inv = uintBitsToFloat(SCENE_INV_255_BITS);
  SST_PRECISE float r = float(v & 0xFFu) * inv;
  SST_PRECISE float g = float((v >> 8u) & 0xFFu) * inv;
  SST_PRECISE float b = float((v >> 16u) & 0xFFu) * inv;
  return vec4(r, g, b, a);
}

// i mod n in [0, n) for n > 0 and any i (GLSL's % is undefined for negative operands).
SST_FUNC int texture_floor_mod(int i, int n) { return i >= 0 ? i % n : (n - 1) - ((-1 - i) % n); }

// A texel coordinate wrapped into [0, n). Repeat and clamp avoid integer division: they are the
// modes real scenes use, on the hottest path of shading.
SST_FUNC int texture_wrap_index(int i, int n, uint mode) {
  if (mode == SCENE_WRAP_CLAMP_TO_EDGE) return clamp(i, 0, n - 1);
  if (mode == SCENE_WRAP_MIRRORED_REPEAT) {
    int period = 2 * n;
    int m = texture_floor_mod(i, period);
    return m < n ? m : period - 1 - m;
  }
  if (i < 0) i += n;
  if (i >= n) i -= n;
  return (i >= 0 && i < n) ? i : texture_floor_mod(i, n);
}

// A repeating coordinate brought into [0, 1) first, so huge or negative uvs cost nothing extra.
SST_FUNC float texture_wrap_reduce(float u, uint mode) {
  SST_PRECISE float r = u - floor(u);
  return mode == SCENE_WRAP_REPEAT ? r : u;
}

// The texture at uv; vec4(1) for a texture without texels. The texels are read in one loop over
// the taps (one for nearest or non-finite uvs, four for bilinear): a shader compiler inlines every
// call of texture_texel with its three decodings, and four calls per sample made the path
// kernels several times larger (Mesa 25's lavapipe compiled `pt` for over a minute).
SST_FUNC vec4 texture_sample(TEXTURE_CTX_PARAM SST_IN(SceneTexture) t, vec2 uv) {
  int w = t.width;
  int h = t.height;
  if (w <= 0 || h <= 0) return vec4(1.0f);
  // Taps at texels r0 + x0, r0 + x1, r1 + x0, r1 + x1, in that order.
  uint x0 = 0u, x1 = 0u, r0 = 0u, r1 = 0u;
  uint taps = 1u;
  float tx = 0.0f, ty = 0.0f;
  if (is_finite(uv.x) && is_finite(uv.y)) {
    // Texel centres sit at half-integers.
    SST_PRECISE float x = texture_wrap_reduce(uv.x, t.wrap_s) * float(w) - 0.5f;
    SST_PRECISE float y = texture_wrap_reduce(uv.y, t.wrap_t) * float(h) - 0.5f;
    x = clamp(x, -float(w) * 1024.0f, float(w) * 1024.0f);  // keep the int conversion exact
    y = clamp(y, -float(h) * 1024.0f, float(h) * 1024.0f);
    if (t.nearest != 0u) {
      SST_PRECISE float xn = x + 0.5f;
      SST_PRECISE float yn = y + 0.5f;
      x0 = uint(texture_wrap_index(int(floor(xn)), w, t.wrap_s));
      r0 = uint(texture_wrap_index(int(floor(yn)), h, t.wrap_t)) * uint(w);
    } else {
      float fx = floor(x);
      float fy = floor(y);
      SST_PRECISE float fracx = x - fx;
      SST_PRECISE float fracy = y - fy;
      tx = fracx;
      ty = fracy;
      x0 = uint(texture_wrap_index(int(fx), w, t.wrap_s));
      x1 = uint(texture_wrap_index(int(fx) + 1, w, t.wrap_s));
      r0 = uint(texture_wrap_index(int(fy), h, t.wrap_t)) * uint(w);
      r1 = uint(texture_wrap_index(int(fy) + 1, h, t.wrap_t)) * uint(w);
      taps = 4u;
    }
  }
  vec4 c00 = vec4(0.0f), c01 = vec4(0.0f), c10 = vec4(0.0f), c11 = vec4(0.0f);
  for (uint k = 0u; k < taps; ++k) {
    vec4 c = texture_texel(TEXTURE_CTX t, ((k & 2u) == 0u ? r0 : r1) + ((k & 1u) == 0u ? x0 : x1));
    if (k == 0u) c00 = c;
    else if (k == 1u) c01 = c;
    else if (k == 2u) c10 = c;
    else c11 = c;
  }
  if (taps == 1u) return c00;
  return texture_mix4(texture_mix4(c00, c01, tx), texture_mix4(c10, c11, tx), ty);
}

SST_END

#endif  // SST_CORE_SCENE_TEXTURE_SAMPLE_H
