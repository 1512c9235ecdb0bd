// Sort keys that order VPLs for the light-tree builders (SST paper eq. 4; docs/design/methods.md):
// primarily by position (Morton code), then by normal direction, then by a unique id, so that
// neighbours in the sorted array are close in space and face the same way.
//
// 64-bit key layout, most significant bit first:
//
//   bit 63 ............ 34 | 33 ........ 25 | 24 ............ 0
//   Morton code (30 bits)  | normal (9 bits) | VPL id (25 bits)
//
// - Morton code: 10 bits per axis, x's bit above y's above z's at every level. Each axis is
//   quantised to 1024 cells over the VPL bounding box; an axis along which the box has no
//   extent maps to 0.
// - Normal code: 3 octant bits (sign of x, y, z; a set bit means negative) followed by 3 levels
//   of 4-way subdivision of the octant's triangle (2 bits each), the paper's scheme after Taubin
//   and Rossignac 1998. See quantize_normal().
// - Id: the VPL's index in its set, which makes every key unique (the radix tree needs that).
//   25 bits: at most kMaxSortKeyVpls = 2^25 = 33,554,432 VPLs; more is an sst::Error.
//
// Shared C++/GLSL source (core/math/cpu_gpu.h): the per-VPL key (vpl_sort_key and its parts) is
// computed by both backends' builders with these functions. A key is held as uvec2 (x = bits
// 0..31, y = bits 32..63) so that no shader needs 64-bit integers; C++ widens it to uint64_t.
// The bounds, the checks and the grid over the bounds are C++ only (the host computes the grid
// for the GPU build too).
#ifndef SST_CORE_LIGHTTREE_SORT_KEY_H
#define SST_CORE_LIGHTTREE_SORT_KEY_H
#include "core/math/morton.h"
#include "core/math/vector_math.h"

SST_BEGIN

SST_CONSTANT int kNormalCodeBits = 9;
SST_CONSTANT int kIdBits = 64 - kMortonBits - kNormalCodeBits;  // 25
SST_CONSTANT int kNormalCodeCount = 1 << kNormalCodeBits;       // 512
// Levels of the 4-way subdivision of an octant's triangle in the normal code.
SST_CONSTANT int kNormalSubdivisionLevels = 3;

// 9-bit code of a direction (need not be unit; a zero vector gets the +x+y+z octant's centre
// cell). quantize_normal(decode_normal(c)) == c for every code c.
SST_FUNC uint quantize_normal(vec3 n) {
  uint code = (n.x < 0.0f ? 4u : 0u) | (n.y < 0.0f ? 2u : 0u) | (n.z < 0.0f ? 1u : 0u);
  // Central projection onto the octant's triangle |x| + |y| + |z| = 1 gives barycentric
  // coordinates (a, b, c) directly.
  vec3 m = vec3(abs(n.x), abs(n.y), abs(n.z));
  SST_PRECISE float sum = m.x + m.y + m.z;
  if (!(sum > 0.0f) || !is_finite(sum)) {
    m = vec3(1.0f);
    sum = 3.0f;
  }
  // Three levels of subdivision make a grid of the lines a, b, c = i / 8, so the cell is known
  // from (floor(8a), floor(8b), floor(8c)) alone. Level by level from the top bit: coordinate
  // x is >= 1/2 in the current triangle iff its bit is set; a corner triangle keeps the lower
  // bits (x' = 2x - 1 or 2x), the middle one complements them (x' = 1 - 2x). Integer bit
  // arithmetic instead of the float comparisons of the recursive definition: random normals
  // mispredict those branches, which made this the most expensive part of a key.
  SST_PRECISE float scale = 8.0f / sum;
  SST_PRECISE float fi = m.x * scale;
  SST_PRECISE float fj = m.y * scale;
  SST_PRECISE float fk = m.z * scale;
  uint i = min(uint(fi), 7u);
  uint j = min(uint(fj), 7u);
  uint k = min(uint(fk), 7u);
  uint flip = 0u;
  for (int level = kNormalSubdivisionLevels - 1; level >= 0; --level) {
    uint ta = ((i >> uint(level)) ^ flip) & 1u;
    uint tb = ((j >> uint(level)) ^ flip) & 1u;
    uint tc = ((k >> uint(level)) ^ flip) & 1u;
    // At most one coordinate is >= 1/2 but for rounding on a border; then x wins over y over z.
    uint corner_b = (ta ^ 1u) & tb;
    uint corner_c = (ta ^ 1u) & (tb ^ 1u) & tc;
    uint middle = (ta | tb | tc) ^ 1u;
    code = (code << 2u) | (corner_b + 2u * corner_c + 3u * middle);
    flip ^= middle;
  }
  return code;
}

// The key morton << 34 | normal_code << 25 | id as (low word, high word).
SST_FUNC uvec2 sort_key_words(uint morton, uint normal_code, uint id) {
  uvec2 key;
  key.x = (normal_code << uint(kIdBits)) | id;
  key.y = (morton << uint(kNormalCodeBits + kIdBits - 32)) | (normal_code >> uint(32 - kIdBits));
  return key;
}

// The key of VPL `id` at `position` with `normal`, over the grid (origin, scale) of the VPL
// bounds.
SST_FUNC uvec2 vpl_sort_key(vec3 position, vec3 normal, uint id, vec3 grid_origin, vec3 grid_scale) {
  return sort_key_words(grid_morton_code(position, grid_origin, grid_scale), quantize_normal(normal), id);
}

SST_END

#ifdef __cplusplus
#include <cstdint>
#include <vector>

#include "core/math/math.h"
#include "core/vpl/vpl.h"

namespace sst {

inline constexpr uint64_t kMaxSortKeyVpls = uint64_t(1) << kIdBits;

inline uint64_t sort_key_from_words(uvec2 key) { return (uint64_t(key.y) << 32) | key.x; }

// The unit direction at the centre (centroid of the triangle cell) of code `code` < 512.
vec3 decode_normal(uint32_t code);

// The VPL index a key carries in its low kIdBits bits.
inline uint32_t sort_key_vpl(uint64_t key) { return uint32_t(key) & uint32_t(kMaxSortKeyVpls - 1); }

inline uint64_t make_sort_key(uint32_t morton, uint32_t normal_code, uint32_t id) {
  return sort_key_from_words(sort_key_words(morton, normal_code, id));
}

// Bounding box of the VPL positions, in parallel. Checks every VPL on the way and throws
// sst::Error naming the first bad one: a non-finite position, a non-finite or zero-length
// normal, a negative or non-finite intensity.
Bounds3 compute_vpl_bounds(const VplSet& vpls);

// Throws sst::Error if `vpl_count` VPLs cannot get unique keys (more than kMaxSortKeyVpls).
void check_sort_key_capacity(size_t vpl_count);

// keys[i] = key of vpls[i] over the grid of `vpl_bounds`, its id bits i (sort_key_vpl).
// Parallel. Throws sst::Error if vpls.size() > kMaxSortKeyVpls.
void compute_sort_keys(const VplSet& vpls, const Bounds3& vpl_bounds, std::vector<uint64_t>& keys);

}  // namespace sst
#endif

#endif  // SST_CORE_LIGHTTREE_SORT_KEY_H
