// Plain arrays into and out of the byte strings of sst's checkpoint formats (the sequence state,
// a ReSTIR history, the gi10 state). An empty array copies nothing: an empty vector's data() may be
// null, and memcpy from or to a null pointer is undefined behaviour even for zero bytes.
#pragma once
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/util/error.h"

namespace sst {

// Appends `count` values from `data` to `out` (a std::string or a std::vector of bytes).
template <class Bytes, class T>
void append_bytes(Bytes& out, const T* data, size_t count = 1) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (count == 0) return;
  const auto* p = reinterpret_cast<const typename Bytes::value_type*>(data);
  out.insert(out.end(), p, p + sizeof(T) * count);
}

// Reads values from the front of a byte string, checking every read against what is left.
// `subject` opens every error message, e.g. "run/state.bin: not a sequence state of this build".
class ByteReader {
 public:
  ByteReader(std::span<const uint8_t> bytes, std::string subject) : bytes_(bytes), subject_(std::move(subject)) {}

  template <class T>
  void read(T* data, size_t count = 1) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (count > left() / sizeof(T)) throw bad("too short");
    if (count == 0) return;
    std::memcpy(data, bytes_.data() + at_, sizeof(T) * count);
    at_ += sizeof(T) * count;
  }
  template <class T>
  void read(std::vector<T>& values, size_t count) {
    if (count > left() / sizeof(T)) throw bad("too short");
    values.resize(count);
    read(values.data(), count);
  }
  template <class T>
  T read() {
    T value;
    read(&value);
    return value;
  }

  // The bytes not read yet; skip() moves past ones read elsewhere.
  std::span<const uint8_t> rest() const { return bytes_.subspan(at_); }
  void skip(size_t n) {
    if (n > left()) throw bad("too short");
    at_ += n;
  }
  size_t left() const { return bytes_.size() - at_; }

  Error bad(const std::string& why) const { return Error(subject_ + " (" + why + ")"); }

 private:
  std::span<const uint8_t> bytes_;
  size_t at_ = 0;
  std::string subject_;
};

}  // namespace sst
