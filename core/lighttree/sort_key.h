// Sort keys that order VPLs for the light-tree builders (SST paper eq. 4, METHODS.md §2):
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
#pragma once
#include <cstdint>
#include <vector>

#include "core/math/math.h"
#include "core/vpl/vpl.h"

namespace sst {

inline constexpr int kMortonBits = 30;
inline constexpr int kNormalCodeBits = 9;
inline constexpr int kIdBits = 64 - kMortonBits - kNormalCodeBits;  // 25
inline constexpr uint64_t kMaxSortKeyVpls = uint64_t(1) << kIdBits;
inline constexpr int kNormalCodeCount = 1 << kNormalCodeBits;  // 512

// 30-bit Morton code of a point whose coordinates are already quantised to [0, 1023].
uint32_t morton_code(uint32_t x, uint32_t y, uint32_t z);

// Quantises positions to the 1024^3 grid over `bounds` (the VPL bounding box).
struct MortonGrid {
  vec3 origin{0.0f};
  vec3 scale{0.0f};  // cells per unit length; 0 along an axis without extent
  static MortonGrid over(const Bounds3& bounds);
  uint32_t code(vec3 p) const;
};

// 9-bit code of a direction (need not be unit; a zero vector gets the +x+y+z octant's centre
// cell). quantize_normal(decode_normal(c)) == c for every code c.
uint32_t quantize_normal(vec3 n);
// The unit direction at the centre (centroid of the triangle cell) of code `code` < 512.
vec3 decode_normal(uint32_t code);

inline uint64_t make_sort_key(uint32_t morton, uint32_t normal_code, uint32_t id) {
  return (uint64_t(morton) << (kNormalCodeBits + kIdBits)) | (uint64_t(normal_code) << kIdBits) | id;
}

// Bounding box of the VPL positions, in parallel. Checks every VPL on the way and throws
// sst::Error naming the first bad one: a non-finite position, a non-finite or zero-length
// normal, a negative or non-finite intensity.
Bounds3 compute_vpl_bounds(const VplSet& vpls);

// Throws sst::Error if `vpl_count` VPLs cannot get unique keys (more than kMaxSortKeyVpls).
void check_sort_key_capacity(size_t vpl_count);

// keys[i] = key of vpls[i] over the grid of `vpl_bounds`; ids[i] = i (the payload the sort
// carries along). Parallel. Throws sst::Error if vpls.size() > kMaxSortKeyVpls.
void compute_sort_keys(const VplSet& vpls, const Bounds3& vpl_bounds, std::vector<uint64_t>& keys,
                       std::vector<uint32_t>& ids);

}  // namespace sst
