// A byte buffer with long runs of zero words stored as the words between them: GI-1.0's caches,
// mostly empty hash tiles, shrink from about 210 MB to a few MB for its sequence checkpoints. The
// encoding is (zero words, literal words, the literal words) repeated, counts as uint32; a tail of
// fewer than four bytes is a literal run of its own.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace sst {

// Appends the encoding of `bytes` to `out`.
void zero_runs_encode(std::span<const uint8_t> bytes, std::vector<uint8_t>& out);

// Decodes an encoding of exactly out.size() bytes from the front of `in` into `out` and returns
// the encoded bytes it read. Throws sst::Error when `in` is not such an encoding.
size_t zero_runs_decode(std::span<const uint8_t> in, std::span<uint8_t> out);

}  // namespace sst
