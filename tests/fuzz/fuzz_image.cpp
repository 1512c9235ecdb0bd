// libFuzzer harness: bytes as an image file of `sst-eval compare` (OpenEXR, Radiance HDR, PNG or
// JPEG, named by their magic so that OpenImageIO picks the same reader), read with read_image,
// which checks the header's size before any pixel is read. Every input must read or be refused
// with sst::Error; anything else is a finding. OpenImageIO itself is not instrumented.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/image/image.h"
#include "core/util/error.h"

namespace {

const char* extension(const uint8_t* d, size_t n) {
  if (n >= 4 && d[0] == 0x76 && d[1] == 0x2F && d[2] == 0x31 && d[3] == 0x01) return ".exr";
  if (n >= 2 && d[0] == '#' && d[1] == '?') return ".hdr";
  if (n >= 2 && d[0] == 0xFF && d[1] == 0xD8) return ".jpg";
  return ".png";
}

}  // namespace

// libFuzzer's entry point; the unit tests compile this file under another name
// (tests/core/fuzz_corpus_test.cpp runs every seed through it).
#ifndef SST_FUZZ_ENTRY
#define SST_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif
extern "C" int SST_FUZZ_ENTRY(const uint8_t* data, size_t size) {
  std::string path = "/tmp/sst-fuzz-image-" + std::to_string(getpid()) + extension(data, size);
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    sst::read_image(path);
  } catch (const sst::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
