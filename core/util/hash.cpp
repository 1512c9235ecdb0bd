#include "core/util/hash.h"

#include <cstdio>
#include <fstream>
#include <vector>

#include "core/util/error.h"

namespace sst {

Hash64& Hash64::add(std::string_view bytes) {
  for (unsigned char c : bytes) {
    h_ ^= c;
    h_ *= 0x100000001b3ull;
  }
  return *this;
}

Hash64& Hash64::add_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read");
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    add(std::string_view(buffer.data(), size_t(in.gcount())));
  }
  return *this;
}

std::string Hash64::hex() const {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h_));
  return text;
}

}  // namespace sst
