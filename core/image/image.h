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

// A named extra layer of an EXR (an AOV): "albedo", "normal", "depth", "direct", "indirect".
// 1-channel layers are written as <name>.Y, 3-channel ones as <name>.R/G/B.
struct Layer {
  std::string name;
  Image image;
};

// Linear -> display: multiply by 2^exposure, clamp to [0,1], sRGB-encode. Keeps channel count.
Image to_display(const Image& linear, float exposure = 0.0f);
// Display (sRGB-encoded) -> linear.
Image from_display(const Image& display);
float srgb_encode(float linear);
float srgb_decode(float encoded);

// Writes by extension: .exr (half? no: float RGB + every layer), .hdr (RGB), .png (display RGB,
// 8-bit). Writes to a temporary file and renames it, so a reader never sees half a file.
// Throws sst::Error naming the path on failure or on an unknown extension.
void write_image(const std::string& path, const Image& rgb, const std::vector<Layer>& layers = {},
                 float exposure = 0.0f);

// Reads RGB (alpha and extra layers dropped) as linear floats. A PNG/JPEG is display-encoded
// as stored and is decoded to linear; `was_display` tells the caller which it was.
Image read_image(const std::string& path, bool* was_display = nullptr);
// Reads one named layer of an EXR written by write_image (e.g. "indirect"); throws if absent.
Image read_layer(const std::string& path, const std::string& layer);

}  // namespace sst
