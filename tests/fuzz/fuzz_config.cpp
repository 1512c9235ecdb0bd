// libFuzzer harness: bytes as an experiment config (configs/*.json), read as read_json_file reads
// a file (the nesting check, then the parser), then parsed and expanded into runs as `sst-eval
// sweep` does before rendering. Malformed JSON and every refused config must end in sst::Error;
// anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>

#include "core/eval/experiment_config.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

// libFuzzer's entry point; the unit tests compile this file under another name
// (tests/core/fuzz_corpus_test.cpp runs every seed through it).
#ifndef SST_FUZZ_ENTRY
#define SST_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif
extern "C" int SST_FUZZ_ENTRY(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    sst::require_json_depth(text, "fuzz.json");
    nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded()) return 0;  // read_json_file's "not valid JSON" error
    sst::ExperimentConfig config = sst::parse_experiment_config(j, "fuzz.json");
    sst::expand_runs(config);
  } catch (const sst::Error&) {
  }
  return 0;
}
