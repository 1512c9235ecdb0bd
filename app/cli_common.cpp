#include "app/cli_common.h"

#include <cstdio>
#include <exception>

#include "core/util/error.h"

namespace sst::app {
int run_guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const sst::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}
}  // namespace sst::app
