#include "app/cli_common.h"

#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>

#include "core/util/error.h"

namespace sst::app {

void print_error(const std::string& message) {
  std::string line;
  for (char c : message) {
    if (c == '\r') continue;
    if (c == '\n') {
      if (!line.empty() && line.back() != ' ') line += "; ";
      continue;
    }
    line += c;
  }
  while (!line.empty() && (line.back() == ' ' || line.back() == ';')) line.pop_back();
  std::fprintf(stderr, "error: %s\n", line.c_str());
}

int parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help, --version
    print_error(e.what());
    return 2;
  }
}

int run_guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const sst::Error& e) {
    print_error(e.what());
  } catch (const std::bad_alloc&) {
    print_error("out of memory");
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.type_error.302] type must be ...": the bracket names the library, not the
    // input; the callers name the file and key where they can.
    std::string what = e.what();
    size_t bracket = what.find("] ");
    print_error(what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos ? what.substr(bracket + 2) : what);
  } catch (const std::exception& e) {
    print_error(e.what());
  }
  return 1;
}

}  // namespace sst::app
