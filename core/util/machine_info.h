// Facts about the machine a run happened on, for every JSON record: numbers are only comparable
// between runs on the same machine.
#pragma once
#include <nlohmann/json.hpp>

namespace sst {
const char* tool_revision();        // git describe of the build (generated at build time)
nlohmann::json machine_info();      // host, cpu model, hardware threads, os, compiler
std::string utc_timestamp();        // ISO 8601
}  // namespace sst
