// core/util/byte_io.h: values and arrays, empty ones included, come back as written, and a read
// past the end is an error naming its subject instead of a read out of bounds.
#include "core/util/byte_io.h"

#include <gtest/gtest.h>

namespace sst {
namespace {

struct Pair {
  int32_t a;
  float b;
};

TEST(ByteIo, ValuesAndArraysComeBackAsWritten) {
  const Pair pair{-3, 2.5f};
  const std::vector<float> floats = {1.0f, -0.0f, 7.25f};
  const std::vector<uint8_t> empty;
  for (bool as_string : {false, true}) {
    std::vector<uint8_t> bytes;
    std::string text;
    auto write = [&](const auto* data, size_t count) {
      if (as_string)
        append_bytes(text, data, count);
      else
        append_bytes(bytes, data, count);
    };
    write(&pair, 1);
    write(empty.data(), empty.size());  // data() of an empty vector: no bytes, no memcpy
    write(floats.data(), floats.size());
    if (as_string) bytes.assign(text.begin(), text.end());
    ASSERT_EQ(bytes.size(), sizeof pair + sizeof(float) * floats.size());

    ByteReader r(bytes, "test bytes");
    const Pair back = r.read<Pair>();
    EXPECT_EQ(back.a, pair.a);
    EXPECT_EQ(back.b, pair.b);
    std::vector<uint8_t> none = {9};
    r.read(none, 0);
    EXPECT_TRUE(none.empty());
    std::vector<float> floats_back;
    r.read(floats_back, floats.size());
    EXPECT_EQ(floats_back, floats);
    EXPECT_EQ(r.left(), 0u);
  }
}

TEST(ByteIo, AReadPastTheEndIsAnErrorNamingItsSubject) {
  std::vector<uint8_t> bytes;
  const uint64_t corrupt_count = uint64_t(1) << 60;
  append_bytes(bytes, &corrupt_count);
  bytes.resize(bytes.size() + 10, 1u);
  ByteReader r(bytes, "state.bin: not a state");
  const uint64_t count = r.read<uint64_t>();
  r.skip(4);
  EXPECT_EQ(r.rest().size(), 6u);
  try {
    std::vector<uint32_t> values;
    r.read(values, count);  // allocates nothing
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "state.bin: not a state (too short)");
  }
  EXPECT_THROW(r.read<uint64_t>(), Error);
  EXPECT_THROW(r.skip(7), Error);
  EXPECT_EQ(r.read<uint32_t>(), 0x01010101u);
  EXPECT_EQ(r.left(), 2u);
}

}  // namespace
}  // namespace sst
