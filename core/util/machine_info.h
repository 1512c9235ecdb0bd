// Facts about the machine a run happened on, for every JSON record: numbers are only comparable
// between runs on the same machine.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace sst {
const char* tool_revision();        // git describe of the build (generated at build time)
nlohmann::json machine_info();      // host, cpu model, hardware threads, os, compiler
std::string utc_timestamp();        // ISO 8601
// The memory this process may use: the lowest of the machine's physical memory, its cgroup's limit
// and SST_MEMORY_LIMIT_MB (for shared machines, and so that fuzzing refuses the same inputs on
// every machine). Sizes read from flags and files are checked against it before anything is allocated.
uint64_t usable_memory_bytes();
}  // namespace sst
