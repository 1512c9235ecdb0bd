// Synthetic inputs of the filter tests and benchmarks: an analytic two-plane depth edge. The left
// part of the image sees a plane facing the camera at depth 2, the right part a plane tilted 45
// degrees at depth 4, the rows above `sky_rows` see nothing; the colour is `left` / `right` times
// (1 + noise u), u uniform in [-1, 1) from a fixed seed, with noise `left_noise` / `right_noise`.
#pragma once
#include <algorithm>
#include <cstdint>
#include <random>

#include "core/image/image.h"

namespace sst::test {

struct TwoPlanes {
  Image color, depth, normal;
  int edge_x = 0;  // first column of the right plane
};

inline TwoPlanes two_planes(int width, int height, vec3 left, vec3 right, float left_noise, float right_noise,
                            uint32_t seed = 7, int sky_rows = 0) {
  TwoPlanes t;
  t.color = Image(width, height, 3);
  t.depth = Image(width, height, 1);
  t.normal = Image(width, height, 3);
  t.edge_x = width / 2;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const vec3 tilted = glm::normalize(vec3(1.0f, 0.0f, 1.0f));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float n = u(rng);
      if (y < sky_rows) continue;  // no hit: depth 0, normal 0, black
      bool is_left = x < t.edge_x;
      t.color.set_rgb(x, y, (is_left ? left : right) * (1.0f + (is_left ? left_noise : right_noise) * n));
      t.depth.at(x, y, 0) = is_left ? 2.0f : 4.0f;
      t.normal.set_rgb(x, y, is_left ? vec3(0.0f, 0.0f, 1.0f) : tilted);
    }
  return t;
}

// The moments and history length SVGF takes, from one frame of `illumination` (history 1: the
// variance comes from the spatial estimate) or `history` frames of the same value.
inline Image single_frame_moments(const Image& illumination) {
  Image m(illumination.width, illumination.height, 2);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      float l = luminance(illumination.rgb(x, y));
      m.at(x, y, 0) = l;
      m.at(x, y, 1) = l * l;
    }
  return m;
}

inline Image constant_image(int width, int height, int channels, float value) {
  Image image(width, height, channels);
  for (float& v : image.data) v = value;
  return image;
}

// The image point-sampled at the centre pixel of each scale x scale block: a G-buffer at 1/scale
// of the resolution, seeing what the full-resolution one sees at the block's centre.
inline Image point_downsample(const Image& image, int scale) {
  Image low((image.width + scale - 1) / scale, (image.height + scale - 1) / scale, image.channels);
  for (int y = 0; y < low.height; ++y)
    for (int x = 0; x < low.width; ++x)
      for (int c = 0; c < image.channels; ++c)
        low.at(x, y, c) = image.at(std::min(x * scale + scale / 2, image.width - 1),
                                   std::min(y * scale + scale / 2, image.height - 1), c);
  return low;
}

}  // namespace sst::test
