// FLIP golden values for tests/core/metrics/flip_test.cpp, computed with NVIDIA's reference
// implementation of FLIP (github.com/NVlabs/flip, BSD 3-Clause; see tests/data/README.md).
//
// Not part of the build: compile it by hand against that repository's single header and paste
// the printed values into flip_test.cpp after changing the test images:
//   g++ -O2 -std=c++17 -ffp-contract=off -I<flip>/src/cpp make_flip_goldens.cpp -o make_flip_goldens
//   ./make_flip_goldens
// The images are defined by formula; flip_test.cpp rebuilds them bit for bit (each value is
// computed in double and rounded to float, as sst's Image stores it). The means printed are the
// double-precision mean of the reference implementation's float error map.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "FLIP.h"

namespace {

double hash01(uint64_t x, uint64_t y, uint64_t c, uint64_t seed) {
  uint32_t h = uint32_t((x * 73856093ull) ^ (y * 19349663ull) ^ (c * 83492791ull) ^ (seed * 2654435761ull));
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h / 4294967296.0;
}

// LDR reference: a smooth colour pattern, a saturated square and a dark one-pixel line.
double ldr_reference(int x, int y, int c) {
  double v = 0.5 + 0.4 * std::sin(0.21 * x + 0.13 * y + 1.7 * c) * std::cos(0.11 * y - 0.07 * x + 0.6 * c);
  if (x >= 20 && x < 34 && y >= 10 && y < 22) v = c == 0 ? 0.95 : 0.15;
  if (x == 45) v = 0.05;
  return v;
}

// LDR test: noise, a colour shift in the lower part, the line moved by one pixel.
double ldr_test(int x, int y, int c) {
  double v = ldr_reference(x, y, c) + 0.12 * (hash01(x, y, c, 3) - 0.5);
  if (y >= 30) v += c == 2 ? 0.08 : -0.03;
  if (x == 45) v = ldr_reference(44, y, c);
  if (x == 46) v = 0.05;
  return std::clamp(v, 0.0, 1.0);
}

// HDR reference: a dim gradient, a bright lamp and a black corner.
double hdr_reference(int x, int y, int c) {
  double v = std::max(0.02 + 0.3 * (x / 64.0) * (y / 48.0) * (1.0 + 0.3 * c) + 0.1 * std::sin(0.3 * x + c), 0.0);
  if (x >= 8 && x < 14 && y >= 6 && y < 12) v = 40.0 + 10.0 * c;
  if (x < 6 && y >= 40) v = 0.0;
  return v;
}

// HDR test: multiplicative noise and fireflies.
double hdr_test(int x, int y, int c) {
  double v = hdr_reference(x, y, c) * (0.6 + 0.8 * hash01(x, y, c, 5));
  if (hash01(x, y, 0, 9) > 0.995) v += 25.0;
  return v;
}

constexpr int kWidth = 64, kHeight = 48;

template <class F>
std::vector<float> make(F value) {
  std::vector<float> v(size_t(kWidth) * kHeight * 3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) v[(size_t(y) * kWidth + x) * 3 + c] = float(value(x, y, c));
  return v;
}

}  // namespace

int main() {
  const int pixels[2][5][2] = {{{1, 19}, {27, 15}, {45, 20}, {46, 20}, {10, 35}},
                               {{12, 10}, {10, 8}, {30, 30}, {2, 45}, {50, 20}}};
  for (int hdr = 0; hdr < 2; ++hdr) {
    std::vector<float> reference = hdr ? make(hdr_reference) : make(ldr_reference);
    std::vector<float> test = hdr ? make(hdr_test) : make(ldr_test);
    FLIP::Parameters parameters;  // 67 ppd; HDR: exposures from the reference, ACES
    float float_mean = 0.0f;
    float* map = nullptr;
    FLIP::evaluate(reference.data(), test.data(), kWidth, kHeight, hdr != 0, parameters, false, true, float_mean, &map);
    double sum = 0.0;
    for (int i = 0; i < kWidth * kHeight; ++i) sum += map[i];
    std::printf("%s: mean %.9f", hdr ? "HDR" : "LDR", sum / (kWidth * kHeight));
    if (hdr)
      std::printf(", exposures %.6f to %.6f, %d of them", parameters.startExposure, parameters.stopExposure,
                  parameters.numExposures);
    std::printf("\n");
    for (const auto& p : pixels[hdr]) std::printf("  (%d, %d): %.9f\n", p[0], p[1], map[p[1] * kWidth + p[0]]);
    delete[] map;
  }
}
