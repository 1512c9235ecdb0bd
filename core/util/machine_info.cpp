#include "core/util/machine_info.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

#include "core/util/error.h"

namespace sst {
namespace {
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}
}  // namespace

uint64_t usable_memory_bytes() {
  uint64_t bytes = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  // cgroup v2 (containers, CI runners, Slurm jobs): "max" or a number of bytes.
  std::ifstream in("/sys/fs/cgroup/memory.max");
  unsigned long long limit = 0;
  if (in >> limit && limit > 0 && limit < bytes) bytes = limit;
  if (const char* env = std::getenv("SST_MEMORY_LIMIT_MB"); env && *env) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long mb = std::strtoull(env, &end, 10);
    if (*end != '\0' || errno == ERANGE || mb < 1 || mb > (uint64_t(1) << 40) || env[0] == '-')
      throw Error("SST_MEMORY_LIMIT_MB must be a whole number of MiB from 1 to 2^40 (got '" + std::string(env) + "')");
    if ((uint64_t(mb) << 20) < bytes) bytes = uint64_t(mb) << 20;
  }
  return bytes;
}

nlohmann::json machine_info() {
  nlohmann::json j;
  char host[256] = {0};
  gethostname(host, sizeof(host) - 1);
  j["host"] = host;
  j["cpu"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  struct utsname u;
  if (uname(&u) == 0) j["os"] = std::string(u.sysname) + " " + u.release + " " + u.machine;
  j["compiler"] = __VERSION__;
  return j;
}

std::string utc_timestamp() {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

}  // namespace sst
