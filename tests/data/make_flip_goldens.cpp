// FLIP golden values for tests/core/metrics/flip_test.cpp, computed with NVIDIA's reference
// implementation of FLIP (github.com/NVlabs/flip, BSD 3-Clause; see tests/data/README.md).
//
// Not part of the build: compile it by hand against that repository's single header and paste
// the printed values into flip_test.cpp after changing the test images:
//   g++ -O2 -std=c++17 -ffp-contract=off -I<flip>/src/cpp make_flip_goldens.cpp -o make_flip_goldens
//   ./make_flip_goldens
// The images are defined by formula in formula_images.h, which flip_test.cpp reads too (each
// value is computed in double and rounded to float, as sst's Image stores it). The means printed are the
// double-precision mean of the reference implementation's float error map.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "FLIP.h"
#include "formula_images.h"

namespace {

namespace formula = sst::test::formula;

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
    std::vector<float> reference = hdr ? make(formula::flip_hdr_reference) : make(formula::flip_ldr_reference);
    std::vector<float> test = hdr ? make(formula::flip_hdr_test) : make(formula::flip_ldr_test);
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
