// Float images and their files. Pixels are linear RGB in memory; display encoding (exposure,
// clamp, sRGB) happens only when writing PNG or when a metric asks for the display image.
#pragma once
#include <string>
#include <vector>

#include "core/math/math.h"

namespace sst {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 3;
  std::vector<float> data;  // row-major, row 0 at the top, channels interleaved

  Image() = default;
  Image(int w, int h, int c = 3) : width(w), height(h), channels(c), data(size_t(w) * h * c, 0.0f) {}
  float& at(int x, int y, int c) { return data[(size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return data[(size_t(y) * width + x) * channels + c]; }
  vec3 rgb(int x, int y) const;
  void set_rgb(int x, int y, vec3 v);
  size_t pixel_count() const { return size_t(width) * height; }
};

// A named extra layer of an EXR (an AOV): "albedo", "normal", "depth", "direct", "indirect",
// "motion". 1-channel layers are written as <name>.Y, 2-channel ones (vectors) as <name>.X/Y,
// 3-channel ones as <name>.R/G/B.
struct Layer {
  std::string name;
  Image image;
};

// Linear -> display: multiply by 2^exposure, clamp to [0,1], sRGB-encode. Keeps channel count.
// Non-finite values become 0.
Image to_display(const Image& linear, float exposure = 0.0f);
// Display (sRGB-encoded) -> linear.
Image from_display(const Image& display);
float srgb_encode(float linear);
float srgb_decode(float encoded);

// Writes by extension: .exr (32-bit float, one part: R,G,B plus the channels of each layer, see
// Layer; layers must match the image's size), .hdr (RGB), .png (8-bit to_display(rgb, exposure),
// rounded to nearest; exposure is used only here). Writes a temporary file beside the target
// and renames it, so a reader never sees half a file; creates missing parent folders.
// Non-finite values are written as 0. Throws sst::Error naming the path on failure or on an
// unknown extension.
// An EXR's values: 32-bit floats, or halves (a third of the file for noisy images; values beyond
// +-65504 are clamped to it).
enum class ExrValues { float32, float16 };
void write_image(const std::string& path, const Image& rgb, const std::vector<Layer>& layers = {},
                 float exposure = 0.0f, ExrValues exr_values = ExrValues::float32);

// Reads RGB (alpha and extra layers dropped) as linear floats. A PNG/JPEG is display-encoded
// as stored and is decoded to linear; `was_display` tells the caller which it was.
Image read_image(const std::string& path, bool* was_display = nullptr);
// Reads one named layer of an EXR written by write_image (e.g. "indirect"): 3 channels, 2 for a
// <layer>.X/Y layer, or 1 for a <layer>.Y layer. Throws if absent, naming the layers the file has.
Image read_layer(const std::string& path, const std::string& layer);

// Like read_image, but returns the values as stored (no sRGB decoding of PNG/JPEG), so that
// metrics on display images see exactly the file's 8-bit levels.
Image read_image_stored(const std::string& path, bool* was_display = nullptr);
// Names of the extra layers of an image file ("albedo", "indirect", ...); empty for plain RGB.
std::vector<std::string> list_layers(const std::string& path);

}  // namespace sst
