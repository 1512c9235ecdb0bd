#include "app/param_flags.h"

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

nlohmann::json ParamFlags::given() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, f] : flags_) {
    if (f.option->count() == 0) continue;
    const std::string flag = "--" + to_flag(name);
    try {
      size_t used = 0;
      if (f.boolean) {
        j[name] = f.boolean_value;
      } else if (f.info.type == "int") {
        long long v = std::stoll(f.text, &used);
        if (used != f.text.size()) throw std::invalid_argument("trailing characters");
        j[name] = v;
      } else if (f.info.type == "float") {
        double v = std::stod(f.text, &used);
        if (used != f.text.size()) throw std::invalid_argument("trailing characters");
        j[name] = v;
      } else {
        j[name] = f.text;
      }
    } catch (const std::exception&) {
      throw Error(flag + " expects " + (f.info.type == "int" ? "an integer" : "a number") + ", got '" + f.text + "'");
    }
  }
  return j;
}

}  // namespace sst::app
