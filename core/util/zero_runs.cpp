#include "core/util/zero_runs.h"

#include <algorithm>
#include <cstring>

#include "core/util/error.h"

namespace sst {
namespace {

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  const uint8_t* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + 4);
}

bool zero_word(const uint8_t* p) {
  uint32_t w;
  std::memcpy(&w, p, 4);
  return w == 0u;
}

}  // namespace

void zero_runs_encode(std::span<const uint8_t> bytes, std::vector<uint8_t>& out) {
  const size_t words = bytes.size() / 4;
  size_t i = 0;
  while (i < words) {
    size_t zeros = 0;
    while (i + zeros < words && zeros < UINT32_MAX && zero_word(&bytes[4 * (i + zeros)])) ++zeros;
    size_t literals = 0;
    while (i + zeros + literals < words && literals < UINT32_MAX && !zero_word(&bytes[4 * (i + zeros + literals)]))
      ++literals;
    put_u32(out, uint32_t(zeros));
    put_u32(out, uint32_t(literals));
    out.insert(out.end(), bytes.begin() + ptrdiff_t(4 * (i + zeros)), bytes.begin() + ptrdiff_t(4 * (i + zeros + literals)));
    i += zeros + literals;
  }
  // The bytes after the last whole word, as literal bytes.
  out.insert(out.end(), bytes.begin() + ptrdiff_t(4 * words), bytes.end());
}

size_t zero_runs_decode(std::span<const uint8_t> in, std::span<uint8_t> out) {
  auto bad = [] { return Error("not a zero-run encoding of this size (truncated or another format)"); };
  std::fill(out.begin(), out.end(), uint8_t(0));
  const size_t size = out.size(), words = size / 4;
  size_t at = 0, i = 0;
  auto get_u32 = [&] {
    if (in.size() - at < 4) throw bad();
    uint32_t v;
    std::memcpy(&v, in.data() + at, 4);
    at += 4;
    return size_t(v);
  };
  while (i < words) {
    const size_t zeros = get_u32(), literals = get_u32();
    if (zeros + literals == 0 || zeros + literals > words - i || 4 * literals > in.size() - at) throw bad();
    i += zeros;
    if (literals > 0) std::memcpy(out.data() + 4 * i, in.data() + at, 4 * literals);
    at += 4 * literals;
    i += literals;
  }
  const size_t tail = size - 4 * words;
  if (in.size() - at < tail) throw bad();
  if (tail > 0) std::memcpy(out.data() + 4 * words, in.data() + at, tail);  // no null pointers to memcpy
  return at + tail;
}

}  // namespace sst
