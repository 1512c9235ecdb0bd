#include "core/image/video.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

extern char** environ;

namespace sst {

std::string encode_video(const std::string& png_pattern, int first_index, double fps, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  std::string tmp = (target.parent_path() / (".tmp." + target.filename().string())).string();
  std::string log = tmp + ".log";
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  // yuv420p for players that know no other; its 2x2 chroma needs even sizes, hence the padding.
  std::vector<std::string> args{"ffmpeg",    "-nostdin", "-y",     "-loglevel", "error",   "-framerate", rate,
                                "-start_number", std::to_string(first_index), "-i", png_pattern,
                                "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                "-crf", "16", "-movflags", "+faststart", "-f", "mp4", tmp};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  int spawned = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  std::string reason;
  if (spawned != 0) {
    reason = "ffmpeg not found (install Debian's ffmpeg for animated previews)";
  } else {
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::ifstream in(log);
      std::string line;
      std::getline(in, line);
      reason = "ffmpeg failed" + (line.empty() ? std::string() : ": " + line);
    } else {
      fs::rename(tmp, target, ec);
      if (ec) reason = "cannot write " + path + ": " + ec.message();
    }
  }
  fs::remove(log, ec);
  if (!reason.empty()) fs::remove(tmp, ec);
  return reason;
}

}  // namespace sst
