#include "core/pipeline/sequence_state.h"

#include <cstring>
#include <fstream>
#include <iterator>

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

template <class T>
void append(std::string& out, const T* data, size_t count) {
  out.append(reinterpret_cast<const char*>(data), sizeof(T) * count);
}

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
  append(out, &h, 1);
  append(out, &state.view, 1);
  append(out, state.positions.data(), state.positions.size());
  append(out, state.temporal.data(), state.temporal.size());
  append(out, state.direct_history.data(), state.direct_history.size());
  append(out, state.method_history.data(), state.method_history.size());
  write_text_atomic(path, out);
}

SequenceState read_sequence_state(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto bad = [&](const std::string& why) { return Error(path + ": not a sequence state of this build (" + why + ")"); };
  Header h, expected;
  if (bytes.size() < sizeof h) throw bad("too short");
  std::memcpy(&h, bytes.data(), sizeof h);
  if (std::memcmp(h.magic, expected.magic, sizeof h.magic) != 0 || h.view_bytes != expected.view_bytes ||
      h.texel_bytes != expected.texel_bytes)
    throw bad("another format");
  const uint64_t limit = bytes.size();
  if (h.positions > limit / sizeof(vec3) || h.texels > limit / sizeof(TemporalTexel) || h.direct_history > limit ||
      h.method_history > limit ||
      sizeof h + sizeof(glsl::ViewParams) + h.positions * sizeof(vec3) + h.texels * sizeof(TemporalTexel) +
              h.direct_history + h.method_history !=
          limit)
    throw bad("its size does not match its counts");
  SequenceState s;
  s.next = h.next;
  s.has_previous = h.has_previous != 0;
  const char* p = bytes.data() + sizeof h;
  std::memcpy(&s.view, p, sizeof s.view);
  p += sizeof s.view;
  s.positions.resize(h.positions);
  std::memcpy(s.positions.data(), p, h.positions * sizeof(vec3));
  p += h.positions * sizeof(vec3);
  s.temporal.resize(h.texels);
  std::memcpy(s.temporal.data(), p, h.texels * sizeof(TemporalTexel));
  p += h.texels * sizeof(TemporalTexel);
  s.direct_history.assign(p, p + h.direct_history);
  p += h.direct_history;
  s.method_history.assign(p, p + h.method_history);
  if (s.next < 0) throw bad("negative frame position");
  return s;
}

}  // namespace sst
