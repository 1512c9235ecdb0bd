#version 450
#extension GL_GOOGLE_include_directive : require
// Radix sort of the GPU light-tree build, pass step 3 of 3: every key of a tile goes to
//   (keys of smaller digits) + (its digit's keys in earlier tiles) + (its rank among the equal
// digits earlier in its tile),
// the scatter of core/math/radix_sort.cpp, which writes a block's elements in input order:
// the pass is stable, so the sort's result is the one stable order of the keys.
//
// Bindings: 0 uvec2 keys_in[], 1 uint ids_in[], 2 uint counts[] (scanned), 3 uint digit_totals[],
// 4 uvec2 keys_out[], 5 uint ids_out[]. Push: count, shift, tile_count.
#include "core/lighttree/light_tree_build_layout.h"
#include "core/math/radix_digit.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer KeysIn { uvec2 keys_in[]; };
layout(std430, binding = 1) readonly buffer IdsIn { uint ids_in[]; };
layout(std430, binding = 2) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 3) readonly buffer DigitTotals { uint digit_totals[]; };
layout(std430, binding = 4) writeonly buffer KeysOut { uvec2 keys_out[]; };
layout(std430, binding = 5) writeonly buffer IdsOut { uint ids_out[]; };

shared uint digit_base[LTB_RADIX];
shared uint tile_digits[LTB_GROUP_SIZE];

void main() {
  uint local = gl_LocalInvocationID.x, tile = ltb_group(), i = ltb_index();
  if (tile >= ltb.tile_count) return;  // a spare group of a two-row dispatch (uniform per group)
  // Exclusive prefix of the digit totals: a Hillis-Steele scan (8 steps).
  uint total = digit_totals[local];
  digit_base[local] = total;
  barrier();
  for (uint step = 1u; step < LTB_RADIX; step <<= 1u) {
    uint add = local >= step ? digit_base[local - step] : 0u;
    barrier();
    digit_base[local] += add;
    barrier();
  }
  uint base = digit_base[local] - total;
  barrier();
  digit_base[local] = base;
  bool in_range = i < ltb.count;
  uvec2 key = in_range ? keys_in[i] : uvec2(0u);
  uint digit = in_range ? radix_digit(key, ltb.shift, LTB_RADIX - 1u) : 0xFFFFFFFFu;
  tile_digits[local] = digit;
  barrier();
  if (!in_range) return;
  uint rank = 0u;
  for (uint j = 0u; j < local; ++j) rank += tile_digits[j] == digit ? 1u : 0u;
  uint slot = digit_base[digit] + counts[digit * ltb.tile_count + tile] + rank;
  keys_out[slot] = key;
  ids_out[slot] = ids_in[i];
}
