// Temporary files that an interrupted run removes: files are written to a temporary name and
// renamed into place, and a SIGINT or SIGTERM between the two would otherwise leave the temporary
// beside the output. A TempFile registers its path for the signal handler for as long as it lives.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sst {

// Installs handlers for SIGINT, SIGTERM and SIGHUP that unlink every registered temporary file
// and then end the process as the signal would have (same signal, default action).
void remove_temp_files_on_signals();

// Whether `target` should be written under a temporary name and renamed into place: true unless
// it exists and is not a regular file. A device or FIFO (--json /dev/null) is written directly;
// renaming a temporary over it would replace /dev/null with a regular file.
bool write_via_rename(const std::string& target);

// Registers `path` while alive; the destructor removes the file unless release() was called
// (after it was renamed into place).
class TempFile {
 public:
  explicit TempFile(std::string path);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }
  // The file was renamed away: neither the destructor nor a signal removes anything.
  void release();

 private:
  std::string path_;
  int slot_ = -1;  // in the signal handler's table; -1 when it was full or after release()
};

// Files written together or not at all: each is written under a temporary name in its target's
// folder (stage), and all are renamed into place by commit(). Destroyed without commit(), the
// temporaries are removed, so that a failure part way leaves none of the outputs.
class StagedFiles {
 public:
  // A temporary path beside `target`, with the same extension (writers choose the format by it);
  // `target` itself when !write_via_rename(target).
  std::string stage(const std::string& target);
  // Calls write(stage(target)); an sst::Error it throws is rethrown naming `target`, not the
  // temporary.
  void write(const std::string& target, const std::function<void(const std::string&)>& write);
  // Renames every staged file to its target; throws sst::Error naming the one that failed.
  void commit();

 private:
  std::vector<std::unique_ptr<TempFile>> temps_;
  std::vector<std::string> targets_;
};

}  // namespace sst
