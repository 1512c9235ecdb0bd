// A stable 64-bit content hash (FNV-1a) for cache keys and run identities: the same bytes give
// the same key on every machine and build, which std::hash does not promise.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace sst {

class Hash64 {
 public:
  Hash64& add(std::string_view bytes);
  // The file's bytes; sst::Error naming the file when it cannot be read.
  Hash64& add_file(const std::string& path);
  uint64_t value() const { return h_; }
  std::string hex() const;  // 16 lowercase hex digits

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace sst
