#include "core/util/temp_files.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/util/error.h"

namespace sst {
namespace {

// A fixed table, so that the handler touches nothing but static memory and async-signal-safe
// calls (unlink, signal, raise). A slot is claimed with an atomic flag and filled before it is
// marked ready.
constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being written, 2 ready
  char path[kPathMax];
};
Slot g_slots[kSlots];

void remove_and_reraise(int sig) {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) unlink(s.path);
  signal(sig, SIG_DFL);
  raise(sig);
}

int claim(const std::string& path) {
  if (path.size() + 1 > kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;  // more than kSlots at once: still removed by the destructor, not by a signal
}

}  // namespace

void remove_temp_files_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_and_reraise;
  sigemptyset(&action.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &action, nullptr);
}

TempFile::TempFile(std::string path) : path_(std::move(path)), slot_(claim(path_)) {}

TempFile::~TempFile() {
  if (path_.empty()) return;
  std::remove(path_.c_str());
  release();
}

void TempFile::release() {
  if (slot_ >= 0) g_slots[slot_].state.store(0);
  slot_ = -1;
  path_.clear();
}

bool write_via_rename(const std::string& target) {
  std::error_code ec;
  std::filesystem::file_status status = std::filesystem::status(target, ec);
  return !std::filesystem::exists(status) || std::filesystem::is_regular_file(status);
}

std::string StagedFiles::stage(const std::string& target) {
  if (!write_via_rename(target)) return target;
  static std::atomic<unsigned> counter{0};
  std::filesystem::path t(target);
  // Appends rather than chains operator+: GCC 12 warns falsely (-Wrestrict) on the chain.
  std::string name = ".";
  name += t.stem().string();
  name += ".staged-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  name += t.extension().string();
  temps_.push_back(std::make_unique<TempFile>((t.parent_path() / name).string()));
  targets_.push_back(target);
  return temps_.back()->path();
}

void StagedFiles::write(const std::string& target, const std::function<void(const std::string&)>& write) {
  const std::string temp = stage(target);
  if (temp == target) return write(target);
  try {
    write(temp);
  } catch (const Error& e) {
    std::string message = e.what();
    for (size_t at = message.find(temp); at != std::string::npos; at = message.find(temp, at + target.size()))
      message.replace(at, temp.size(), target);
    throw Error(message);
  }
}

void StagedFiles::commit() {
  for (size_t i = 0; i < temps_.size(); ++i) {
    std::error_code ec;
    std::filesystem::rename(temps_[i]->path(), targets_[i], ec);
    if (ec) throw Error("cannot write " + targets_[i] + ": " + ec.message());
    temps_[i]->release();
  }
  temps_.clear();
  targets_.clear();
}

}  // namespace sst
