// Morton codes of points on a 1024^3 grid, in the common subset of C++ and GLSL: the order in
// which light trees lay out their lights (the VPL sort keys of core/lighttree/sort_key.h, the
// emitter tree of core/lights/emitter_tree_build.h). 10 bits per axis, x's bit above y's above
// z's at every level.
#ifndef SST_CORE_MATH_MORTON_H
#define SST_CORE_MATH_MORTON_H
#include "core/math/vector_math.h"

SST_BEGIN

SST_CONSTANT int kMortonBits = 30;

// Spreads the low 10 bits of x so that two zero bits follow each one.
SST_FUNC uint expand_bits_10(uint x) {
  x &= 0x3FFu;
  x = (x * 0x00010001u) & 0xFF0000FFu;
  x = (x * 0x00000101u) & 0x0F00F00Fu;
  x = (x * 0x00000011u) & 0xC30C30C3u;
  x = (x * 0x00000005u) & 0x49249249u;
  return x;
}

// 30-bit Morton code of a point whose coordinates are already quantised to [0, 1023].
SST_FUNC uint morton_code(uint x, uint y, uint z) {
  return (expand_bits_10(x) << 2u) | (expand_bits_10(y) << 1u) | expand_bits_10(z);
}

// The grid cell of coordinate p along one axis: min(max((p - origin) * scale, 0), 1023),
// truncated. Never NaN for finite p: the grid's scale is finite.
SST_FUNC uint quantize_axis(float p, float origin, float scale) {
  SST_PRECISE float cell = (p - origin) * scale;
  cell = cell < 0.0f ? 0.0f : cell;
  cell = 1023.0f < cell ? 1023.0f : cell;
  return uint(cell);
}

// Morton code of position p on the 1024^3 grid with corner `origin` and `scale` cells per unit
// length (MortonGrid).
SST_FUNC uint grid_morton_code(vec3 p, vec3 origin, vec3 scale) {
  return morton_code(quantize_axis(p.x, origin.x, scale.x), quantize_axis(p.y, origin.y, scale.y),
                     quantize_axis(p.z, origin.z, scale.z));
}

SST_END

#ifdef __cplusplus
#include "core/math/math.h"

namespace sst {

// Quantises positions to the 1024^3 grid over `bounds` (e.g. the VPL bounding box).
struct MortonGrid {
  vec3 origin{0.0f};
  vec3 scale{0.0f};  // cells per unit length; 0 along an axis without extent
  static MortonGrid over(const Bounds3& bounds);
  uint32_t code(vec3 p) const { return grid_morton_code(p, origin, scale); }
};

}  // namespace sst
#endif

#endif  // SST_CORE_MATH_MORTON_H
