// The one precondition every metric shares: test and reference have the same shape.
#pragma once
#include <string>

#include "core/image/image.h"
#include "core/util/error.h"

namespace sst {

inline std::string shape_string(const Image& image) {
  // Appends rather than chains operator+: GCC 12 warns falsely (-Wrestrict) on the chain.
  std::string s = std::to_string(image.width);
  s += 'x';
  s += std::to_string(image.height);
  if (image.channels != 3) {
    s += 'x';
    s += std::to_string(image.channels);
  }
  return s;
}

inline void require_same_shape(const Image& test, const Image& reference) {
  if (test.width != reference.width || test.height != reference.height || test.channels != reference.channels)
    throw Error("image sizes differ: test is " + shape_string(test) + ", reference is " +
                shape_string(reference));
}

}  // namespace sst
