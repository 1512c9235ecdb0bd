#include "core/scene/texture.h"

namespace sst {
namespace {
int wrap_index(int i, int n, Wrap mode) {
  switch (mode) {
    case Wrap::ClampToEdge: return std::clamp(i, 0, n - 1);
    case Wrap::MirroredRepeat: {
      int period = 2 * n;
      int m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    case Wrap::Repeat:
    default: return ((i % n) + n) % n;
  }
}
}  // namespace

vec4 Texture::sample(vec2 uv) const {
  if (width <= 0 || height <= 0) return vec4(1.0f);
  // Texel centres sit at half-integers; floor() keeps negative coordinates wrapping correctly.
  float x = uv.x * float(width) - 0.5f;
  float y = uv.y * float(height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return texels[0];
  x = std::fmod(x, float(width) * 1024.0f);  // keep floor() exact for huge uvs
  y = std::fmod(y, float(height) * 1024.0f);
  if (nearest) {
    int ix = wrap_index(int(std::floor(x + 0.5f)), width, wrap_s);
    int iy = wrap_index(int(std::floor(y + 0.5f)), height, wrap_t);
    return texels[size_t(iy) * width + ix];
  }
  float fx = std::floor(x), fy = std::floor(y);
  float tx = x - fx, ty = y - fy;
  int x0 = wrap_index(int(fx), width, wrap_s), x1 = wrap_index(int(fx) + 1, width, wrap_s);
  int y0 = wrap_index(int(fy), height, wrap_t), y1 = wrap_index(int(fy) + 1, height, wrap_t);
  auto at = [&](int xi, int yi) { return texels[size_t(yi) * width + xi]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tx), glm::mix(at(x0, y1), at(x1, y1), tx), ty);
}
}  // namespace sst
