#include "core/scene/texture.h"

#include <array>

#include "core/image/image.h"

namespace sst {
namespace {

const std::array<float, 256>& srgb_decode_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgb_decode(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// Wraps a texel coordinate into [0, n). Repeat and clamp avoid integer division: they are the
// modes real scenes use, on the hottest path of shading.
int wrap_index(int i, int n, Wrap mode) {
  switch (mode) {
    case Wrap::ClampToEdge: return std::clamp(i, 0, n - 1);
    case Wrap::MirroredRepeat: {
      int period = 2 * n;
      int m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    case Wrap::Repeat:
    default:
      if (i < 0) i += n;
      if (i >= n) i -= n;
      return (i >= 0 && i < n) ? i : ((i % n) + n) % n;
  }
}

// Brings a repeating coordinate into [0, 1) first, so huge or negative uvs cost nothing extra.
float reduce(float u, Wrap mode) { return mode == Wrap::Repeat ? u - std::floor(u) : u; }

}  // namespace

vec4 Texture::texel(size_t i) const {
  if (!texels.empty()) return texels[i];
  uint32_t v = rgba8[i];
  float a = float(v >> 24) / 255.0f;
  if (srgb) {
    const auto& t = srgb_decode_table();
    return {t[v & 0xFF], t[(v >> 8) & 0xFF], t[(v >> 16) & 0xFF], a};
  }
  return {float(v & 0xFF) * (1.0f / 255.0f), float((v >> 8) & 0xFF) * (1.0f / 255.0f),
          float((v >> 16) & 0xFF) * (1.0f / 255.0f), a};
}

vec4 Texture::sample(vec2 uv) const {
  if (width <= 0 || height <= 0) return vec4(1.0f);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return texel(0);
  // Texel centres sit at half-integers.
  float x = reduce(uv.x, wrap_s) * float(width) - 0.5f;
  float y = reduce(uv.y, wrap_t) * float(height) - 0.5f;
  x = std::clamp(x, -float(width) * 1024.0f, float(width) * 1024.0f);  // keep int conversion exact
  y = std::clamp(y, -float(height) * 1024.0f, float(height) * 1024.0f);
  if (nearest) {
    int ix = wrap_index(int(std::floor(x + 0.5f)), width, wrap_s);
    int iy = wrap_index(int(std::floor(y + 0.5f)), height, wrap_t);
    return texel(size_t(iy) * width + ix);
  }
  float fx = std::floor(x), fy = std::floor(y);
  float tx = x - fx, ty = y - fy;
  int x0 = wrap_index(int(fx), width, wrap_s), x1 = wrap_index(int(fx) + 1, width, wrap_s);
  int y0 = wrap_index(int(fy), height, wrap_t), y1 = wrap_index(int(fy) + 1, height, wrap_t);
  size_t r0 = size_t(y0) * width, r1 = size_t(y1) * width;
  return glm::mix(glm::mix(texel(r0 + x0), texel(r0 + x1), tx), glm::mix(texel(r1 + x0), texel(r1 + x1), tx), ty);
}

}  // namespace sst
