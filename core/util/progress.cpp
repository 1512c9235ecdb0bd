#include "core/util/progress.h"

#include <unistd.h>

#include <cstdio>

namespace sst {

Progress::Progress(std::string label, uint64_t total, bool quiet)
    : label_(std::move(label)), total_(total), quiet_(quiet), terminal_(isatty(STDERR_FILENO)) {
  start_ = last_print_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

void Progress::advance(uint64_t n) {
  uint64_t done = done_.fetch_add(n) + n;
  if (quiet_) return;
  auto now = std::chrono::steady_clock::now();
  double since_start = std::chrono::duration<double>(now - start_).count();
  if (since_start < 1.0) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  double since_print = std::chrono::duration<double>(now - last_print_).count();
  if (since_print < (terminal_ ? 0.2 : 5.0) && printed_) return;
  last_print_ = now;
  print(done, false);
}

void Progress::finish() {
  if (quiet_ || !printed_) return;
  std::lock_guard lock(mutex_);
  if (!printed_) return;
  print(done_.load(), true);
  printed_ = false;
}

void Progress::print(uint64_t done, bool final_line) {
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double fraction = total_ ? double(done) / double(total_) : 1.0;
  double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    constexpr int kWidth = 30;
    int filled = int(fraction * kWidth + 0.5);
    std::fprintf(stderr, "\r%s [%.*s%*s] %5.1f%%  %.1fs elapsed, %.1fs left ", label_.c_str(), filled,
                 "##############################", kWidth - filled, "", 100.0 * fraction, elapsed, left);
    if (final_line) std::fputc('\n', stderr);
  } else {
    std::fprintf(stderr, "%s: %.0f%% (%.1fs elapsed, %.1fs left)\n", label_.c_str(), 100.0 * fraction, elapsed, left);
  }
  std::fflush(stderr);
  printed_ = true;
}

}  // namespace sst
