// Bad input is reported by throwing sst::Error with a one-line message that names the file, key
// or value at fault; the front ends print it as "error: <message>" and exit non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace sst {
struct Error : std::runtime_error {
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};
}  // namespace sst
