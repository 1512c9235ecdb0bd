// Test images defined by formula, so that a golden value computed by another implementation (a
// Python or C++ program in this folder, run by hand) and the test that checks it see the same
// pixels without an image file. Plain C++ on purpose: the golden programs compile it without sst.
// Each value is computed in double; the tests round it to float as sst's Image stores it.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sst::test::formula {

// A hash of (x, y, channel, seed) to [0, 1): the images' noise.
inline double hash01(uint64_t x, uint64_t y, uint64_t c, uint64_t seed) {
  uint32_t h = uint32_t((x * 73856093ull) ^ (y * 19349663ull) ^ (c * 83492791ull) ^ (seed * 2654435761ull));
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h / 4294967296.0;
}

// FLIP's images (tests/core/metrics/flip_test.cpp, tests/data/make_flip_goldens.cpp), 64 x 48.
// LDR reference: a smooth colour pattern, a saturated square and a dark one-pixel line.
inline double flip_ldr_reference(int x, int y, int c) {
  double v = 0.5 + 0.4 * std::sin(0.21 * x + 0.13 * y + 1.7 * c) * std::cos(0.11 * y - 0.07 * x + 0.6 * c);
  if (x >= 20 && x < 34 && y >= 10 && y < 22) v = c == 0 ? 0.95 : 0.15;
  if (x == 45) v = 0.05;
  return v;
}

// LDR test: noise, a colour shift in the lower part, the line moved by one pixel.
inline double flip_ldr_test(int x, int y, int c) {
  double v = flip_ldr_reference(x, y, c) + 0.12 * (hash01(x, y, c, 3) - 0.5);
  if (y >= 30) v += c == 2 ? 0.08 : -0.03;
  if (x == 45) v = flip_ldr_reference(44, y, c);
  if (x == 46) v = 0.05;
  return std::clamp(v, 0.0, 1.0);
}

// HDR reference: a dim gradient, a bright lamp and a black corner.
inline double flip_hdr_reference(int x, int y, int c) {
  double v = std::max(0.02 + 0.3 * (x / 64.0) * (y / 48.0) * (1.0 + 0.3 * c) + 0.1 * std::sin(0.3 * x + c), 0.0);
  if (x >= 8 && x < 14 && y >= 6 && y < 12) v = 40.0 + 10.0 * c;
  if (x < 6 && y >= 40) v = 0.0;
  return v;
}

// HDR test: multiplicative noise and fireflies.
inline double flip_hdr_test(int x, int y, int c) {
  double v = flip_hdr_reference(x, y, c) * (0.6 + 0.8 * hash01(x, y, c, 5));
  if (hash01(x, y, 0, 9) > 0.995) v += 25.0;
  return v;
}

}  // namespace sst::test::formula
