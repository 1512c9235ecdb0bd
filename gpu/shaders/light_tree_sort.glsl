// What the radix-sort shaders of the GPU light-tree build share (light_tree_sort_*.comp).
#ifndef SST_GPU_SHADERS_LIGHT_TREE_SORT_GLSL
#define SST_GPU_SHADERS_LIGHT_TREE_SORT_GLSL

// Bits [shift, shift + 8) of a 64-bit key held as uvec2 (x low, y high word).
uint key_digit(uvec2 key, uint shift) {
  uint bits;
  if (shift >= 32u)
    bits = key.y >> (shift - 32u);
  else if (shift == 0u)
    bits = key.x;
  else
    bits = (key.x >> shift) | (key.y << (32u - shift));
  return bits & (LTB_RADIX - 1u);
}

#endif
