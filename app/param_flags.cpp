#include "app/param_flags.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/util/error.h"

namespace sst::app {

void ParamFlags::add(CLI::App& app, const std::vector<ParamInfo>& table, const std::string& group) {
  for (const ParamInfo& p : table) {
    if (flags_.count(p.name)) continue;
    Flag& f = flags_[p.name];
    f.info = p;
    std::string name = "--" + to_flag(p.name);
    std::string help = p.help + " [default: " + p.default_value.dump() + "]";
    if (p.type == "bool") {
      f.boolean = true;
      f.option = app.add_flag(name + ",!--no-" + to_flag(p.name), f.boolean_value, help)->group(group);
    } else {
      f.option = app.add_option(name, f.text, help)->group(group)->type_name(
          p.type == "int" ? "INT" : p.type == "float" ? "FLOAT" : "TEXT");
    }
  }
}

namespace {

// The flag's text as a JSON number of the flag's type, or null when it is not one or does not fit
// the parameter's range. Integers are read as 64-bit (signed or not) and range-checked rather than
// narrowed; floats must be finite.
nlohmann::json parse_number(const std::string& text, const ParamInfo& info) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return nullptr;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  nlohmann::json value;
  if (info.type == "int") {
    if (text[0] == '-') value = (long long)std::strtoll(begin, &end, 10);
    else value = (unsigned long long)std::strtoull(begin, &end, 10);
  } else {
    value = std::strtod(begin, &end);
  }
  if (errno == ERANGE || end != begin + text.size()) return nullptr;
  if (info.type == "float" && !std::isfinite(value.get<double>())) return nullptr;
  if (!info.min_value.is_null() && (value < info.min_value || value > info.max_value)) return nullptr;
  return value;
}

}  // namespace

nlohmann::json ParamFlags::given() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, f] : flags_) {
    if (f.option->count() == 0) continue;
    if (f.boolean) {
      j[name] = f.boolean_value;
    } else if (f.info.type == "int" || f.info.type == "float") {
      nlohmann::json value = parse_number(f.text, f.info);
      if (value.is_null())
        throw Error("--" + to_flag(name) + " expects " + range_text(f.info) + ", got '" + f.text + "'");
      j[name] = value;
    } else {
      j[name] = f.text;
    }
  }
  return j;
}

}  // namespace sst::app
