#version 450
#extension GL_GOOGLE_include_directive : require
// Sort keys of the GPU light-tree build: the GLSL twin of compute_sort_keys in
// core/lighttree/sort_key.cpp (MortonGrid::code, quantize_normal, make_sort_key), bit for bit.
// One invocation per VPL i: keys[i] = its 64-bit key as uvec2 (x low, y high word), ids[i] = i.
//
// Bindings: 0 GpuVpl vpls[], 1 uvec2 keys[], 2 uint ids[]. Push: LightTreeBuildPush (count,
// grid_origin, grid_scale; the grid is MortonGrid::over(vpl bounds), computed on the host).
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) writeonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 2) writeonly buffer Ids { uint ids[]; };

// Spreads the low 10 bits of x so that two zero bits follow each one (sort_key.cpp's expand_bits_10).
uint expand_bits_10(uint x) {
  x &= 0x3FFu;
  x = (x * 0x00010001u) & 0xFF0000FFu;
  x = (x * 0x00000101u) & 0x0F00F00Fu;
  x = (x * 0x00000011u) & 0xC30C30C3u;
  x = (x * 0x00000005u) & 0x49249249u;
  return x;
}

// quantize_axis: min(max((p - origin) * scale, 0), 1023) as std::min/std::max, then truncation.
uint quantize_axis(float p, float origin, float scale) {
  precise float cell = (p - origin) * scale;
  cell = cell < 0.0 ? 0.0 : cell;
  cell = 1023.0 < cell ? 1023.0 : cell;
  return uint(cell);
}

uint morton_code(vec3 p) {
  uint x = quantize_axis(p.x, ltb.grid_origin.x, ltb.grid_scale.x);
  uint y = quantize_axis(p.y, ltb.grid_origin.y, ltb.grid_scale.y);
  uint z = quantize_axis(p.z, ltb.grid_origin.z, ltb.grid_scale.z);
  return (expand_bits_10(x) << 2) | (expand_bits_10(y) << 1) | expand_bits_10(z);
}

// quantize_normal: octant bits, then three levels of the 4-way subdivision by integer bit
// arithmetic on (floor(8a), floor(8b), floor(8c)); see sort_key.cpp for why this is the cell.
uint quantize_normal(vec3 n) {
  uint code = (n.x < 0.0 ? 4u : 0u) | (n.y < 0.0 ? 2u : 0u) | (n.z < 0.0 ? 1u : 0u);
  vec3 m = abs(n);
  precise float sum = m.x + m.y + m.z;
  if (!(sum > 0.0) || isinf(sum) || isnan(sum)) {
    m = vec3(1.0);
    sum = 3.0;
  }
  precise float scale = 8.0 / sum;
  precise float fi = m.x * scale, fj = m.y * scale, fk = m.z * scale;
  uint i = min(uint(fi), 7u), j = min(uint(fj), 7u), k = min(uint(fk), 7u);
  uint flip = 0u;
  for (int level = 2; level >= 0; --level) {
    uint ta = ((i >> level) ^ flip) & 1u, tb = ((j >> level) ^ flip) & 1u, tc = ((k >> level) ^ flip) & 1u;
    uint corner_b = (ta ^ 1u) & tb, corner_c = (ta ^ 1u) & (tb ^ 1u) & tc;
    uint middle = (ta | tb | tc) ^ 1u;
    code = (code << 2) | (corner_b + 2u * corner_c + 3u * middle);
    flip ^= middle;
  }
  return code;
}

void main() {
  uint i = ltb_index();
  if (i >= ltb.count) return;
  uint morton = morton_code(vpls[i].position);
  uint normal_code = quantize_normal(vpls[i].normal);
  // key = morton << 34 | normal_code << 25 | i (kMortonBits 30, kNormalCodeBits 9, kIdBits 25).
  keys[i] = uvec2((normal_code << 25) | i, (morton << 2) | (normal_code >> 7));
  ids[i] = i;
}
