#include "core/util/json_io.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <sstream>

#include "core/util/error.h"
#include "core/util/temp_files.h"

namespace sst {

void write_text_atomic(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  fs::path target(path);
  if (!write_via_rename(path)) {  // a device or FIFO: written in place, never renamed over
    std::ofstream out(path, std::ios::binary);
    if (!(out << text) || !out.flush()) throw Error("cannot write " + path);
    return;
  }
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  fs::path temp = target;
  temp += ".tmp-" + std::to_string(getpid());
  TempFile guard(temp.string());  // an interrupted or failed write leaves no temporary
  {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw Error("cannot write " + path);
    out << text;
    if (!out.flush()) throw Error("cannot write " + path);
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) throw Error("cannot write " + path + ": " + ec.message());
  guard.release();
}

void write_json_atomic(const std::string& path, const nlohmann::json& j) { write_text_atomic(path, j.dump(2) + "\n"); }

size_t json_nesting_depth(std::string_view text) {
  size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

void require_json_depth(std::string_view text, const std::string& name) {
  if (json_nesting_depth(text) > kMaxJsonDepth)
    throw Error(name + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

nlohmann::json read_json_file(const std::string& path) {
  std::error_code ec;
  // A FIFO would block the read forever, a directory reads as an error of the parser.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  require_json_depth(text, path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    throw Error(path + ": malformed JSON (" + what.substr(what.find(']') + 2) + ")");
  }
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace sst
