// CLI flags generated from parameter tables: every RenderOptions field and every parameter of
// every registered method becomes --<name-with-dashes>; what the user gave is collected as JSON
// (the same keys a sweep config uses).
#pragma once
#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/util/params.h"

namespace sst::app {

class ParamFlags {
 public:
  // Adds one flag per parameter of `table` to `app` (once per name across calls).
  void add(CLI::App& app, const std::vector<ParamInfo>& table, const std::string& group);
  // The flags given on the command line, as {"snake_name": typed value}.
  nlohmann::json given() const;

 private:
  struct Flag {
    ParamInfo info;
    CLI::Option* option = nullptr;
    std::string text;
    bool boolean = false;
    bool boolean_value = false;  // what a boolean flag was set to (--x, --x=false, --no-x)
  };
  std::map<std::string, Flag> flags_;
};

}  // namespace sst::app
