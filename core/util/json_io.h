// JSON files written atomically (temp file + rename) so an interrupted run never leaves half a
// record, and read with one-line errors naming the file.
#pragma once
#include <nlohmann/json.hpp>
#include <cstddef>
#include <string>
#include <string_view>

namespace sst {
void write_json_atomic(const std::string& path, const nlohmann::json& j);
// Reads and parses a JSON file; malformed JSON, or JSON nested deeper than kMaxJsonDepth, is an
// sst::Error naming the file.
nlohmann::json read_json_file(const std::string& path);

// The deepest nesting of arrays and objects any JSON file we read may have. Parsers, copies and
// dumps of JSON recurse once per level, so a few kilobytes of "[[[[..." would overflow the stack;
// real configs and glTF files nest fewer than 20 levels.
constexpr size_t kMaxJsonDepth = 256;
// The deepest nesting of arrays and objects in JSON text: brackets outside strings, counted in one
// pass without recursion (malformed text is left to the parser).
size_t json_nesting_depth(std::string_view text);
// Throws sst::Error "<name>: JSON nested deeper than 256 levels" when text is nested deeper.
void require_json_depth(std::string_view text, const std::string& name);
// v, or null where v is not finite: JSON has no NaN or infinity.
nlohmann::json number_or_null(double v);
// Writes `text` to `path` atomically, creating parent directories.
void write_text_atomic(const std::string& path, const std::string& text);
}  // namespace sst
