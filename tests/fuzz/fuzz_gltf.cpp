// libFuzzer harness: bytes as a glTF file (JSON text, or GLB by its magic) through sst's loader
// and its coordinate check, as sst-render reads a scene. Every input must load or be refused with
// sst::Error. A crash, a sanitizer report, any other exception, a run over -timeout or a heap over
// -rss_limit_mb is a finding. External URIs resolve in a folder that does not exist.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene/gltf_loader.h"
#include "core/util/error.h"

// libFuzzer's entry point; the unit tests compile this file under another name
// (tests/core/fuzz_corpus_test.cpp runs every seed through it).
#ifndef SST_FUZZ_ENTRY
#define SST_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif
extern "C" int SST_FUZZ_ENTRY(const uint8_t* data, size_t size) {
  try {
    sst::Scene scene = sst::load_gltf_from_memory(std::string_view(reinterpret_cast<const char*>(data), size),
                                                  "/nonexistent-sst-fuzz", "fuzz.gltf");
    sst::check_coordinates(scene);
  } catch (const sst::Error&) {
  }
  return 0;
}
