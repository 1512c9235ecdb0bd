#version 450
#extension GL_GOOGLE_include_directive : require
// Radix sort of the GPU light-tree build, pass step 2 of 3: one workgroup per digit turns its row
// of per-tile counts into exclusive offsets within the digit, and writes the digit's total (the
// scatter adds the totals of the smaller digits), the offsets exclusive_offsets in
// core/math/radix_sort.cpp computes for its blocks. Each invocation scans a run of
// ceil(tile_count / 256) counts: short loops however many VPLs there are (lavapipe ends an
// invocation's loops after 65535 iterations; 2^25 VPLs make runs of 512).
//
// Bindings: 0 uint counts[LTB_RADIX * tile_count] (in place), 1 uint digit_totals[LTB_RADIX].
// Push: tile_count. Dispatch: LTB_RADIX workgroups.
#include "core/lighttree/light_tree_build_layout.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) buffer Counts { uint counts[]; };
layout(std430, binding = 1) writeonly buffer DigitTotals { uint digit_totals[]; };

shared uint run_sums[LTB_GROUP_SIZE];

void main() {
  uint digit = gl_WorkGroupID.x, local = gl_LocalInvocationID.x;
  uint run = (ltb.tile_count + LTB_GROUP_SIZE - 1u) / LTB_GROUP_SIZE;
  uint row = digit * ltb.tile_count;
  uint begin = min(local * run, ltb.tile_count), end = min(begin + run, ltb.tile_count);
  uint sum = 0u;
  for (uint t = begin; t < end; ++t) sum += counts[row + t];
  run_sums[local] = sum;
  barrier();
  // Exclusive prefix of the runs: a Hillis-Steele scan over the 256 sums (8 steps).
  for (uint step = 1u; step < LTB_GROUP_SIZE; step <<= 1u) {
    uint add = local >= step ? run_sums[local - step] : 0u;
    barrier();
    run_sums[local] += add;
    barrier();
  }
  uint offset = run_sums[local] - sum;
  for (uint t = begin; t < end; ++t) {
    uint c = counts[row + t];
    counts[row + t] = offset;
    offset += c;
  }
  if (local == LTB_GROUP_SIZE - 1u) digit_totals[digit] = run_sums[local];
}
