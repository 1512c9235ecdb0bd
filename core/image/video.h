// Animated previews of rendered sequences: PNG frames encoded as an MP4 (H.264) by Debian's ffmpeg,
// which the HTML report and any browser play.
#pragma once
#include <string>

namespace sst {

// Encodes the PNG files `png_pattern` (a printf pattern with one integer, e.g. "dir/f_%04d.png")
// numbered from `first_index` on, at `fps`, into `path`, written beside it under a temporary name
// and renamed when complete. Returns "" on success, else a one-line reason (ffmpeg not installed,
// its error); it never throws, because a preview is never worth a sequence's images.
std::string encode_video(const std::string& png_pattern, int first_index, double fps, const std::string& path);

}  // namespace sst
