#version 450
#extension GL_GOOGLE_include_directive : require
// Radix sort of the GPU light-tree build, pass step 1 of 3: the histogram of one 8-bit digit per
// tile of LTB_GROUP_SIZE keys (the per-block histograms of core/math/radix_sort.cpp, with
// blocks of 256 keys). counts[digit * tile_count + tile]: digit-major, so that an exclusive scan
// of the array in order gives each (digit, tile) its first output slot, tiles in input order
// within a digit, which keeps the pass stable.
//
// Bindings: 0 uvec2 keys[], 1 uint counts[LTB_RADIX * tile_count]. Push: count, shift, tile_count.
#include "core/lighttree/light_tree_build_layout.h"
#include "core/math/radix_digit.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 1) writeonly buffer Counts { uint counts[]; };

shared uint histogram[LTB_RADIX];

void main() {
  uint local = gl_LocalInvocationID.x, tile = ltb_group(), i = ltb_index();
  if (tile >= ltb.tile_count) return;  // a spare group of a two-row dispatch (uniform per group)
  histogram[local] = 0u;
  barrier();
  if (i < ltb.count) atomicAdd(histogram[radix_digit(keys[i], ltb.shift, LTB_RADIX - 1u)], 1u);
  barrier();
  counts[local * ltb.tile_count + tile] = histogram[local];
}
