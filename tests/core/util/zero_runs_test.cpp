// core/util/zero_runs.h: buffers with runs of zero words come back byte for byte, shrink by their
// zeros, and a cut or foreign encoding is an error.
#include "core/util/zero_runs.h"

#include <gtest/gtest.h>

#include <random>

#include "core/util/error.h"

namespace sst {
namespace {

TEST(ZeroRuns, BuffersComeBackByteForByte) {
  std::mt19937 rng(7);
  for (size_t size : {size_t(0), size_t(3), size_t(4), size_t(1001), size_t(65536 + 2)}) {
    std::vector<uint8_t> bytes(size, 0u);
    // Runs of non-zero bytes between runs of zeros, the last word's bytes too.
    for (size_t i = 0; i < size; ++i)
      if ((i / 37) % 3 == 1 || i + 2 >= size) bytes[i] = uint8_t(1 + rng() % 255);
    std::vector<uint8_t> encoded = {0xAB};  // encodings append
    zero_runs_encode(bytes, encoded);
    std::vector<uint8_t> back(size, 0xCD);
    EXPECT_EQ(zero_runs_decode(std::span<const uint8_t>(encoded).subspan(1), back), encoded.size() - 1);
    EXPECT_EQ(back, bytes) << size;
  }
}

TEST(ZeroRuns, ZerosShrinkToCounts) {
  std::vector<uint8_t> bytes(1 << 20, 0u);
  bytes[4096] = 5;
  std::vector<uint8_t> encoded;
  zero_runs_encode(bytes, encoded);
  EXPECT_LT(encoded.size(), 32u);
}

TEST(ZeroRuns, CutOrForeignEncodingsAreErrors) {
  std::vector<uint8_t> bytes(400, 0u);
  for (size_t i = 100; i < 200; ++i) bytes[i] = 9;
  std::vector<uint8_t> encoded, back(bytes.size()), longer(bytes.size() + 400);
  zero_runs_encode(bytes, encoded);
  EXPECT_THROW(zero_runs_decode(std::span<const uint8_t>(encoded).first(encoded.size() - 1), back), Error);
  EXPECT_THROW(zero_runs_decode(encoded, longer), Error);
  const std::vector<uint8_t> nothing(8, 0u);  // runs of no words
  EXPECT_THROW(zero_runs_decode(nothing, back), Error);
}

}  // namespace
}  // namespace sst
