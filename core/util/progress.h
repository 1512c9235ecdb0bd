// Progress of a long render on stderr: a bar when stderr is a terminal, a line every few seconds
// otherwise (logs), nothing for work that ends within a second or when quiet.
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace sst {

class Progress {
 public:
  Progress(std::string label, uint64_t total, bool quiet);
  ~Progress();
  void advance(uint64_t n = 1);  // thread-safe
  void finish();

 private:
  void print(uint64_t done, bool final_line);
  std::string label_;
  uint64_t total_;
  bool quiet_, terminal_;
  bool printed_ = false;
  std::atomic<uint64_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace sst
