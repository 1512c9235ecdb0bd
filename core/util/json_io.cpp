#include "core/util/json_io.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/error.h"

namespace sst {

void write_text_atomic(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  fs::path temp = target;
  temp += ".tmp-" + std::to_string(getpid());
  {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw Error("cannot write " + path);
    out << text;
    if (!out.flush()) throw Error("cannot write " + path);
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp);
    throw Error("cannot write " + path + ": " + ec.message());
  }
}

void write_json_atomic(const std::string& path, const nlohmann::json& j) { write_text_atomic(path, j.dump(2) + "\n"); }

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot open " + path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    throw Error(path + ": malformed JSON (" + what.substr(what.find(']') + 2) + ")");
  }
}

}  // namespace sst
