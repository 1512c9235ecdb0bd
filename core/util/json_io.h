// JSON files written atomically (temp file + rename) so an interrupted run never leaves half a
// record, and read with one-line errors naming the file.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace sst {
void write_json_atomic(const std::string& path, const nlohmann::json& j);
nlohmann::json read_json_file(const std::string& path);
// Writes `text` to `path` atomically, creating parent directories.
void write_text_atomic(const std::string& path, const std::string& text);
}  // namespace sst
