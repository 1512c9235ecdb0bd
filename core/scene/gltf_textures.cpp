#include "core/scene/gltf_textures.h"

#include <stb/stb_image.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <utility>

#include "core/image/image.h"
#include "core/scene/encoded_image.h"
#include "core/util/machine_info.h"

namespace sst::gltf {
namespace {

// The largest texture side GPUs accept; larger ones are refused before decoding.
constexpr int kMaxTextureSide = 16384;

Wrap wrap_mode(int gl_wrap, Warnings& warnings) {
  switch (gl_wrap) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
    default:
      warnings.add("unknown sampler wrap mode " + std::to_string(gl_wrap) + ": REPEAT used");
      return Wrap::Repeat;
  }
}

bool valid_decoded(const tinygltf::Image& img) {
  if (img.width < 1 || img.height < 1 || img.component < 1 || img.component > 4) return false;
  if (img.bits != 8 && img.bits != 16) return false;
  return img.image.size() >= size_t(img.width) * size_t(img.height) * size_t(img.component) * size_t(img.bits / 8);
}

// An 8- or 16-bit image with 1-4 channels -> RGBA (grey expands to RGB, missing alpha is 1).
// 8-bit images stay 8-bit, sRGB-encoded if colour (decoded per fetch); 16-bit ones become
// linear floats. Colour textures are sRGB; alpha never is.
Texture to_texture(const tinygltf::Image& img, bool srgb) {
  Texture t;
  t.width = img.width;
  t.height = img.height;
  size_t texels = size_t(img.width) * size_t(img.height);
  int channels = img.component;
  auto expand = [channels](auto channel, auto one) {
    using T = decltype(one);
    std::array<T, 4> v{T(0), T(0), T(0), one};
    if (channels <= 2) {
      v[0] = v[1] = v[2] = channel(0);
      if (channels == 2) v[3] = channel(1);
    } else {
      for (int c = 0; c < 3; ++c) v[c] = channel(c);
      if (channels == 4) v[3] = channel(3);
    }
    return v;
  };
  if (img.bits == 8) {
    t.srgb = srgb;
    t.rgba8.resize(texels);
    for (size_t i = 0; i < texels; ++i) {
      const unsigned char* p = img.image.data() + i * channels;
      auto v = expand([p](int c) { return uint32_t(p[c]); }, uint32_t(255));
      t.rgba8[i] = v[0] | (v[1] << 8) | (v[2] << 16) | (v[3] << 24);
    }
    return t;
  }
  t.texels.resize(texels);
  for (size_t i = 0; i < texels; ++i) {
    const unsigned char* p = img.image.data() + i * channels * 2;
    auto v = expand(
        [p, srgb](int c) {
          uint16_t raw;
          std::memcpy(&raw, p + 2 * c, 2);
          float f = float(raw) / 65535.0f;
          return srgb && c < 3 ? srgb_decode(f) : f;
        },
        1.0f);
    t.texels[i] = vec4(v[0], v[1], v[2], v[3]);
  }
  return t;
}

std::string image_label(const Context& ctx, int index) {
  const tinygltf::Image& img = ctx.model.images[index];
  if (!img.uri.empty() && img.uri.rfind("data:", 0) != 0) return "'" + img.uri + "'";
  return quoted_name("image", index, img.name);
}

// The encoded bytes of an image: from its file or data URI (kept by keep_encoded_image), or
// from its bufferView, bounds-checked.
std::pair<const unsigned char*, size_t> encoded_image(const Context& ctx, const Accessors& accessors, int index) {
  const tinygltf::Image& img = ctx.model.images[index];
  if (img.bufferView >= 0) {
    size_t len = size_t(img.bufferView) < ctx.model.bufferViews.size() ? ctx.model.bufferViews[img.bufferView].byteLength : 0;
    return {accessors.checked_bytes(img.bufferView, 0, len, 1, 1, "image " + std::to_string(index)), len};
  }
  if (img.image.empty()) ctx.fail("image " + image_label(ctx, index) + " not found, empty or not a regular file");
  return {img.image.data(), img.image.size()};
}

// glTF 2.0 allows PNG and JPEG only; stb would also read other formats, some of them wrongly
// (16-bit PNM), so anything else is refused rather than risk a silently wrong texture.
void require_png_or_jpeg(const Context& ctx, int index, std::pair<const unsigned char*, size_t> bytes) {
  auto [p, n] = bytes;
  bool png = n >= 8 && std::memcmp(p, "\x89PNG\r\n\x1a\n", 8) == 0;
  bool jpeg = n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF;
  if (!png && !jpeg) ctx.fail("image " + image_label(ctx, index) + " is neither PNG nor JPEG (the formats glTF 2.0 allows)");
}

void apply_sampler(Context& ctx, int sampler, Texture& t) {
  if (sampler < 0) return;  // glTF: no sampler = repeat, auto filtering
  const tinygltf::Sampler& s = ctx.model.samplers[sampler];
  t.wrap_s = wrap_mode(s.wrapS, ctx.warnings);
  t.wrap_t = wrap_mode(s.wrapT, ctx.warnings);
  t.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
}

}  // namespace

bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::vector<Texture> decode_textures(Context& ctx, const Accessors& accessors, const std::vector<TextureKey>& keys) {
  std::vector<int> image_ids;
  for (const TextureKey& k : keys)
    if (std::find(image_ids.begin(), image_ids.end(), k.image) == image_ids.end()) image_ids.push_back(k.image);
  std::vector<std::pair<const unsigned char*, size_t>> encoded;
  uint64_t decoded_bytes = 0;
  const uint64_t budget = usable_memory_bytes() / 4;
  for (int id : image_ids) {
    encoded.push_back(encoded_image(ctx, accessors, id));
    require_png_or_jpeg(ctx, id, encoded.back());
    // The header's size is checked before stb allocates it (decompression bombs), and a JPEG's
    // Huffman tables before stb indexes them (see encoded_image.h).
    EncodedImageHeader header;
    if (std::string why = read_encoded_image_header(encoded.back().first, encoded.back().second, header); !why.empty())
      ctx.fail("cannot decode image " + image_label(ctx, id) + ": " + why);
    if (header.width > kMaxTextureSide || header.height > kMaxTextureSide)
      ctx.fail("image " + image_label(ctx, id) + " is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
               " pixels: textures may have at most " + std::to_string(kMaxTextureSide) + " per side");
    // Decoded as stored, then converted to RGBA: 8-bit to 4 bytes a texel, 16-bit to 16.
    decoded_bytes += uint64_t(header.width) * uint64_t(header.height) *
                     uint64_t(header.channels * header.bytes_per_channel + (header.bytes_per_channel == 2 ? 16 : 4));
    if (decoded_bytes > budget)
      ctx.fail("the textures up to image " + image_label(ctx, id) + " need " + std::to_string(decoded_bytes >> 20) +
               " MiB decoded, more than a quarter of this machine's memory (" + std::to_string(usable_memory_bytes() >> 20) + " MiB)");
  }
  std::vector<tinygltf::Image> decoded(image_ids.size());
  std::vector<std::string> errors(image_ids.size());
  tbb::parallel_for(size_t(0), image_ids.size(), [&](size_t i) {
    std::string err, warn;
    auto [bytes, size] = encoded[i];
    if (size > size_t(INT32_MAX)) err = "image larger than 2 GiB";
    else if (!tinygltf::LoadImageData(&decoded[i], image_ids[i], &err, &warn, 0, 0, bytes, int(size), nullptr))
      // tinygltf's own text only says "unsupported image format"; stb's reason (a thread-local
      // of this thread, which just decoded) says what is wrong. Some corrupt PNGs leave that
      // reason empty, and an empty error here once let the undecoded image through (fuzzing).
      err = stbi_failure_reason() && *stbi_failure_reason() ? stbi_failure_reason() : "cannot decode";
    else if (!valid_decoded(decoded[i]))
      err = "unsupported pixel layout (" + std::to_string(decoded[i].component) + " channels, " +
            std::to_string(decoded[i].bits) + " bits)";
    errors[i] = err;
  });
  for (size_t i = 0; i < image_ids.size(); ++i)
    if (!errors[i].empty()) ctx.fail("cannot decode image " + image_label(ctx, image_ids[i]) + ": " + first_line(errors[i]));
  std::vector<size_t> slot_of_key(keys.size());
  for (size_t k = 0; k < keys.size(); ++k)
    slot_of_key[k] = std::find(image_ids.begin(), image_ids.end(), keys[k].image) - image_ids.begin();
  std::vector<Texture> textures(keys.size());
  tbb::parallel_for(size_t(0), keys.size(), [&](size_t k) { textures[k] = to_texture(decoded[slot_of_key[k]], keys[k].srgb); });
  for (size_t k = 0; k < keys.size(); ++k) apply_sampler(ctx, keys[k].sampler, textures[k]);
  return textures;
}

}  // namespace sst::gltf
