#include "core/pipeline/sequence_state.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/util/byte_io.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace sst {
namespace {

// The layout sizes are part of the magic: a build whose structs differ cannot misread the file.
struct Header {
  char magic[8] = {'S', 'S', 'T', 'S', 'E', 'Q', '2', '\0'};
  uint32_t view_bytes = sizeof(glsl::ViewParams);
  uint32_t texel_bytes = sizeof(TemporalTexel);
  int32_t next = 0;
  int32_t has_previous = 0;
  uint64_t positions = 0;
  uint64_t texels = 0;
  uint64_t direct_history = 0;  // bytes
  uint64_t method_history = 0;
};

}  // namespace

void write_sequence_state(const std::string& path, const SequenceState& state) {
  Header h;
  h.next = state.next;
  h.has_previous = state.has_previous ? 1 : 0;
  h.positions = state.positions.size();
  h.texels = state.temporal.size();
  h.direct_history = state.direct_history.size();
  h.method_history = state.method_history.size();
  std::string out;
  append_bytes(out, &h);
  append_bytes(out, &state.view);
  append_bytes(out, state.positions.data(), state.positions.size());
  append_bytes(out, state.temporal.data(), state.temporal.size());
  append_bytes(out, state.direct_history.data(), state.direct_history.size());
  append_bytes(out, state.method_history.data(), state.method_history.size());
  write_text_atomic(path, out);
}

SequenceState read_sequence_state(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ByteReader r({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()},
               path + ": not a sequence state of this build");
  const Header h = r.read<Header>();
  const Header expected;
  if (std::memcmp(h.magic, expected.magic, sizeof h.magic) != 0 || h.view_bytes != expected.view_bytes ||
      h.texel_bytes != expected.texel_bytes)
    throw r.bad("another format");
  SequenceState s;
  s.next = h.next;
  s.has_previous = h.has_previous != 0;
  r.read(&s.view);
  r.read(s.positions, h.positions);
  r.read(s.temporal, h.texels);
  r.read(s.direct_history, h.direct_history);
  r.read(s.method_history, h.method_history);
  if (r.left() != 0) throw r.bad("its size does not match its counts");
  if (s.next < 0) throw r.bad("negative frame position");
  return s;
}

}  // namespace sst
