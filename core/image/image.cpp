#include "core/image/image.h"

#include <OpenImageIO/imageio.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

#include "core/util/error.h"
#include "core/util/machine_info.h"
#include "core/util/temp_files.h"

namespace sst {
namespace fs = std::filesystem;

namespace {

enum class FileFormat { exr, hdr, png };

// OIIO error text can span lines; our errors are one line.
std::string one_line(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message.empty() ? "unknown error" : message;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

FileFormat format_for(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return FileFormat::exr;
  if (ext == ".hdr") return FileFormat::hdr;
  if (ext == ".png") return FileFormat::png;
  throw Error("unsupported image extension '" + fs::path(path).extension().string() + "' in " + path +
              " (use .exr, .png or .hdr)");
}

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.0f; }

// Same folder (so rename is atomic) and same extension (so OIIO picks the same writer).
fs::path temp_path_for(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  // Appends rather than chains operator+: GCC 12 warns falsely (-Wrestrict) on the chain.
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  name += path.extension().string();
  return path.parent_path() / name;
}

void check_writable(const std::string& path, const Image& rgb, const std::vector<Layer>& layers) {
  if (rgb.width <= 0 || rgb.height <= 0 || rgb.channels <= 0 ||
      rgb.data.size() != size_t(rgb.width) * rgb.height * rgb.channels)
    throw Error("cannot write image " + path + ": empty or inconsistent image (" + std::to_string(rgb.width) +
                "x" + std::to_string(rgb.height) + "x" + std::to_string(rgb.channels) + ")");
  std::set<std::string> names;
  for (const Layer& layer : layers) {
    const Image& im = layer.image;
    if (layer.name.empty() || layer.name.find('.') != std::string::npos || !names.insert(layer.name).second)
      throw Error("cannot write image " + path + ": bad or duplicate layer name '" + layer.name + "'");
    if (im.width != rgb.width || im.height != rgb.height || (im.channels < 1 || im.channels > 3) ||
        im.data.size() != size_t(im.width) * im.height * im.channels)
      throw Error("cannot write image " + path + ": layer '" + layer.name + "' is " +
                  std::to_string(im.width) + "x" + std::to_string(im.height) + "x" +
                  std::to_string(im.channels) + ", expected " + std::to_string(rgb.width) + "x" +
                  std::to_string(rgb.height) + " with 1, 2 or 3 channels");
  }
}

struct Pixels {
  OIIO::ImageSpec spec;
  std::vector<float> floats;
  std::vector<uint8_t> bytes;
  const void* data() const { return bytes.empty() ? static_cast<const void*>(floats.data()) : bytes.data(); }
  OIIO::TypeDesc data_format() const { return bytes.empty() ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8; }
};

// Channel names: R, G, B, then per layer <layer>.Y, <layer>.X/Y (a 2D vector, as motion vectors
// are stored) or <layer>.R/G/B.
std::vector<std::string> exr_channel_names(const std::vector<Layer>& layers) {
  std::vector<std::string> names{"R", "G", "B"};
  for (const Layer& layer : layers) {
    if (layer.image.channels == 1) {
      names.push_back(layer.name + ".Y");
    } else if (layer.image.channels == 2) {
      for (const char* c : {".X", ".Y"}) names.push_back(layer.name + c);
    } else {
      for (const char* c : {".R", ".G", ".B"}) names.push_back(layer.name + c);
    }
  }
  return names;
}

Pixels pack_float(const Image& rgb, const std::vector<Layer>& layers) {
  Pixels px;
  const std::vector<std::string> names = exr_channel_names(layers);
  const int nch = int(names.size());
  px.spec = OIIO::ImageSpec(rgb.width, rgb.height, nch, OIIO::TypeDesc::FLOAT);
  px.spec.channelnames = names;
  px.floats.resize(rgb.pixel_count() * nch);
  for (int y = 0; y < rgb.height; ++y) {
    for (int x = 0; x < rgb.width; ++x) {
      float* out = &px.floats[(size_t(y) * rgb.width + x) * nch];
      const vec3 c = rgb.rgb(x, y);
      *out++ = finite_or_zero(c.x);
      *out++ = finite_or_zero(c.y);
      *out++ = finite_or_zero(c.z);
      for (const Layer& layer : layers)
        for (int k = 0; k < layer.image.channels; ++k) *out++ = finite_or_zero(layer.image.at(x, y, k));
    }
  }
  return px;
}

Pixels pack_display(const Image& rgb, float exposure) {
  Pixels px;
  px.spec = OIIO::ImageSpec(rgb.width, rgb.height, 3, OIIO::TypeDesc::UINT8);
  px.spec.attribute("oiio:ColorSpace", "sRGB");
  px.bytes.resize(rgb.pixel_count() * 3);
  const float scale = std::exp2(exposure);
  for (int y = 0; y < rgb.height; ++y) {
    for (int x = 0; x < rgb.width; ++x) {
      const vec3 c = rgb.rgb(x, y);
      uint8_t* out = &px.bytes[(size_t(y) * rgb.width + x) * 3];
      for (int k = 0; k < 3; ++k) {
        const float v = finite_or_zero(c[k] * scale);
        out[k] = uint8_t(std::lround(srgb_encode(std::clamp(v, 0.0f, 1.0f)) * 255.0f));
      }
    }
  }
  return px;
}

void write_with_oiio(const fs::path& temp, const std::string& path, const Pixels& px) {
  auto fail = [&](const std::string& why) {
    std::error_code ec;
    fs::remove(temp, ec);
    throw Error("cannot write image " + path + ": " + one_line(why));
  };
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out) fail(OIIO::geterror());
  if (!out->open(temp.string(), px.spec)) fail(out->geterror());
  if (!out->write_image(px.data_format(), px.data())) fail(out->geterror());
  if (!out->close()) fail(out->geterror());
  out.reset();
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) fail(ec.message());
}

// libpng, under OIIO's PNG reader, prints "libpng error: ..." on stderr itself, and OIIO then
// reports the same text to us, which our one-line error already carries. While a PNG is opened
// and read, stderr (fd 2) goes to /dev/null; these reads are short and made by one thread.
class QuietStderrForPng {
 public:
  explicit QuietStderrForPng(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return;  // opening a FIFO would block; open_input refuses it
    unsigned char magic[8] = {};
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
      size_t n = std::fread(magic, 1, 8, f);
      std::fclose(f);
      if (n != 8 || std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) != 0) return;
    } else {
      return;
    }
    int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null_fd < 0) return;
    std::fflush(stderr);
    saved_ = ::dup(2);
    if (saved_ >= 0) ::dup2(null_fd, 2);
    ::close(null_fd);
  }
  ~QuietStderrForPng() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
  }
  QuietStderrForPng(const QuietStderrForPng&) = delete;
  QuietStderrForPng& operator=(const QuietStderrForPng&) = delete;

 private:
  int saved_ = -1;
};

// The most pixels an image we read may have: the largest render (render_pixel_limit's cap).
constexpr uint64_t kMaxReadPixels = uint64_t(1) << 28;
// Bytes per channel value while reading: the file's own values (a double at most), the floats
// converted from them and the Image gathered from those (8 + 4 + 4).
constexpr uint64_t kReadBytesPerValue = 16;

// Refuses an image of width x height pixels of `channels` values (plus `extra_bytes` of the
// reader's own) that we would not read: a size below 1, more pixels than kMaxReadPixels, or more
// memory than a quarter of the machine's. Sizes are 64-bit: a header's may exceed 32 bits.
void check_read_size(const std::string& path, int64_t width, int64_t height, int64_t channels, uint64_t extra_bytes) {
  if (width < 1 || height < 1 || channels < 1)
    throw Error("cannot read image " + path + ": invalid size " + std::to_string(width) + "x" +
                std::to_string(height) + " with " + std::to_string(channels) + " channels");
  if (uint64_t(width) > kMaxReadPixels || uint64_t(height) > kMaxReadPixels ||
      uint64_t(width) * uint64_t(height) > kMaxReadPixels)
    throw Error("cannot read image " + path + ": " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels is too large (at most " + std::to_string(kMaxReadPixels) + " pixels)");
  // At most 2^28 pixels x 2^31 channels x 16 bytes: the product fits in 64 bits.
  const uint64_t values_bytes = uint64_t(width) * uint64_t(height) * uint64_t(channels) * kReadBytesPerValue;
  const uint64_t bytes = values_bytes + std::min(extra_bytes, ~uint64_t(0) - values_bytes);
  if (const uint64_t memory = usable_memory_bytes(); bytes > memory / 4)
    throw Error("cannot read image " + path + ": " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels of " + std::to_string(channels) + " channels need " + std::to_string(bytes >> 20) +
                " MiB to read, more than a quarter of this machine's memory (" + std::to_string(memory >> 20) + " MiB)");
}

// "" when every attribute of an OpenEXR file's header(s) declares a size that fits in the file,
// else what does not; throws, as open_input does, for a header whose data window and channel list
// check_read_size refuses. OpenEXR 3.1 (through OpenImageIO 2.4) allocates an attribute's declared
// size before reading it, so a 500-byte file could ask for 2 GB, and sizes buffers from the data
// window as it opens a file (a 552-byte file declaring one line of 16M pixels had it allocate
// 200-MB buffers; both found by fuzzing): so the headers are walked here first. Per attribute a
// name and a type (null-terminated, under 256 bytes), a 32-bit size and the value; an empty name
// ends a header, and multi-part files (version flag 0x1000) end their list of headers with an
// empty one.
std::string check_exr_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char head[8];
  if (!in.read(reinterpret_cast<char*>(head), 8)) return "";
  if (!(head[0] == 0x76 && head[1] == 0x2F && head[2] == 0x31 && head[3] == 0x01)) return "";  // not OpenEXR
  const bool multipart = (head[5] & 0x10) != 0;
  in.seekg(0, std::ios::end);
  const uint64_t file_size = uint64_t(in.tellg());
  uint64_t pos = 8;
  auto read_name = [&](std::string& name) {
    name.clear();
    in.seekg(std::streamoff(pos));
    for (char c; in.get(c);) {
      ++pos;
      if (c == '\0') return true;
      if (name.size() >= 255) return false;
      name.push_back(c);
    }
    return false;
  };
  auto int32_at = [](const unsigned char* b) {
    return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
  };
  for (int header = 0; header < 65536; ++header) {
    std::string name, type;
    bool first = true;
    int64_t width = 0, height = 0, channels = 0;
    bool has_window = false;
    for (;;) {
      if (!read_name(name)) return "truncated or malformed header";
      if (name.empty()) break;
      first = false;
      if (!read_name(type)) return "truncated or malformed header";
      unsigned char size_bytes[4];
      if (!in.read(reinterpret_cast<char*>(size_bytes), 4)) return "truncated header";
      pos += 4;
      const int32_t size = int32_at(size_bytes);
      if (size < 0 || pos + uint64_t(size) > file_size)
        return "header attribute '" + name + "' declares " + std::to_string(size) + " bytes, " +
               std::to_string(file_size - pos) + " follow";
      if (name == "dataWindow" && type == "box2i" && size == 16) {
        unsigned char box[16];  // xmin, ymin, xmax, ymax
        if (!in.read(reinterpret_cast<char*>(box), 16)) return "truncated header";
        width = int64_t(int32_at(box + 8)) - int32_at(box) + 1;
        height = int64_t(int32_at(box + 12)) - int32_at(box + 4) + 1;
        has_window = true;
      } else if (name == "channels" && type == "chlist") {
        // Per channel a null-terminated name and 16 bytes (type, pLinear, reserved, sampling);
        // an empty name ends the list.
        std::string list(size_t(size), '\0');
        if (!in.read(list.data(), size)) return "truncated header";
        for (size_t at = 0; at < list.size() && list[at] != '\0'; ++channels) {
          const size_t end = list.find('\0', at);
          if (end == std::string::npos) break;
          at = end + 1 + 16;
        }
      }
      pos += uint64_t(size);
    }
    if (has_window) check_read_size(path, width, height, std::max<int64_t>(channels, 1), 0);
    if (!multipart || first) return "";
  }
  return "too many headers";
}

// The buffer OpenImageIO allocates itself while reading a tiled file in its own types: one tile,
// whose size the header declares. (Scanline files are read straight into our buffer.) Saturates
// instead of wrapping.
uint64_t oiio_tile_bytes(const OIIO::ImageSpec& spec) {
  if (spec.tile_width < 1) return 0;
  constexpr uint64_t kHuge = ~uint64_t(0);
  auto mul = [](uint64_t a, uint64_t b) { return (b != 0 && a > kHuge / b) ? kHuge : a * b; };
  return mul(mul(mul(uint64_t(spec.tile_width), uint64_t(std::max(spec.tile_height, 1))),
                 uint64_t(std::max(spec.tile_depth, 1))),
             uint64_t(spec.pixel_bytes(true)));
}

std::unique_ptr<OIIO::ImageInput> open_input(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("cannot read image " + path + ": no such file");
  if (fs::is_directory(path, ec)) throw Error("cannot read image " + path + ": is a directory");
  if (!fs::is_regular_file(path, ec)) throw Error("cannot read image " + path + ": not a regular file");  // a FIFO blocks
  if (std::string why = check_exr_header(path); !why.empty())
    throw Error("cannot read image " + path + ": invalid OpenEXR file: " + why);
  OIIO::ImageSpec config;
  // Keep PNG colour values as stored; OIIO would otherwise premultiply by alpha.
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error("cannot read image " + path + ": " + one_line(OIIO::geterror()));
  // The header's size is checked before the pixels are allocated: a PNG of a few dozen bytes can
  // declare 30000x30000 pixels (a decompression bomb).
  // A header may declare a negative size (an OpenEXR data window whose max lies below its min;
  // found by fuzzing), which check_read_size refuses before any product is taken.
  const OIIO::ImageSpec& spec = in->spec();
  check_read_size(path, spec.width, spec.height, spec.nchannels, oiio_tile_bytes(spec));
  return in;
}

// Integer-coded files are display-encoded in practice (PNG, JPEG, 8/16-bit TIFF).
bool is_display_encoded(const OIIO::ImageInput& in) {
  const std::string format = in.format_name();
  const auto base = in.spec().format.basetype;
  return format == "png" || format == "jpeg" || base == OIIO::TypeDesc::UINT8 ||
         base == OIIO::TypeDesc::UINT16;
}

// All channels of subimage 0 as floats; integer levels are divided by their maximum exactly.
// The pixels are read in the file's own types into a zeroed buffer and converted here:
// OpenImageIO's own conversion reads through a buffer of at least 256 whole scanlines, however few
// the image has (a 1-row image 8 million pixels wide asked for 24 GiB; found by fuzzing), and
// left uninitialised where a truncated file has no data.
std::vector<float> read_all_channels(OIIO::ImageInput& in, const std::string& path) {
  const OIIO::ImageSpec& spec = in.spec();
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  const size_t channels = size_t(spec.nchannels);
  const size_t pixel_bytes = spec.pixel_bytes(true);
  std::vector<unsigned char> native(pixels * pixel_bytes);
  if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, native.data()))
    throw Error("cannot read image " + path + ": " + one_line(in.geterror()));
  std::vector<float> values(pixels * channels);
  size_t offset = 0;
  for (size_t c = 0; c < channels; ++c) {
    const OIIO::TypeDesc type = spec.channelformat(int(c));
    const unsigned char* from = native.data() + offset;
    if (type == OIIO::TypeDesc::UINT8) {
      for (size_t p = 0; p < pixels; ++p) values[p * channels + c] = float(from[p * pixel_bytes]) / 255.0f;
    } else if (type == OIIO::TypeDesc::UINT16) {
      for (size_t p = 0; p < pixels; ++p) {
        uint16_t level;
        std::memcpy(&level, from + p * pixel_bytes, sizeof(level));
        values[p * channels + c] = float(level) / 65535.0f;
      }
    } else if (!OIIO::convert_image(1, spec.width, spec.height, 1, from, type, OIIO::stride_t(pixel_bytes),
                                    OIIO::stride_t(pixel_bytes * size_t(spec.width)), OIIO::AutoStride,
                                    values.data() + c, OIIO::TypeDesc::FLOAT, OIIO::stride_t(channels * sizeof(float)),
                                    OIIO::stride_t(channels * sizeof(float) * size_t(spec.width)), OIIO::AutoStride)) {
      throw Error("cannot read image " + path + ": channel " + std::to_string(c) + " has the unsupported type " + type.c_str());
    }
    offset += type.size();
  }
  return values;
}

int channel_index(const OIIO::ImageSpec& spec, const std::string& name) {
  for (int i = 0; i < spec.nchannels; ++i)
    if (spec.channelnames[i] == name) return i;
  return -1;
}

Image gather(const OIIO::ImageSpec& spec, const std::vector<float>& values,
             const std::vector<int>& channels) {
  Image out(spec.width, spec.height, int(channels.size()));
  for (size_t p = 0; p < out.pixel_count(); ++p)
    for (size_t k = 0; k < channels.size(); ++k)
      out.data[p * channels.size() + k] = values[p * spec.nchannels + channels[k]];
  return out;
}

// R,G,B by name (multi-layer EXRs); else Y or a single channel replicated; else the first three.
std::vector<int> rgb_channels(const OIIO::ImageSpec& spec) {
  const int r = channel_index(spec, "R"), g = channel_index(spec, "G"), b = channel_index(spec, "B");
  if (r >= 0 && g >= 0 && b >= 0) return {r, g, b};
  const int y = channel_index(spec, "Y");
  if (y >= 0) return {y, y, y};
  if (spec.nchannels < 3) return {0, 0, 0};
  return {0, 1, 2};
}

std::vector<std::string> layer_names(const OIIO::ImageSpec& spec) {
  std::set<std::string> names;
  for (const std::string& channel : spec.channelnames) {
    const auto dot = channel.rfind('.');
    if (dot != std::string::npos && dot > 0) names.insert(channel.substr(0, dot));
  }
  return {names.begin(), names.end()};
}

// v = f(v) for every value, in parallel: each value on its own, so threads change no bit.
template <typename F>
void for_each_value(Image& image, F f) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, image.data.size(), 1 << 16),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i < r.end(); ++i) image.data[i] = f(image.data[i]);
                    });
}

}  // namespace

vec3 Image::rgb(int x, int y) const {
  const float* p = &data[(size_t(y) * width + x) * channels];
  return channels >= 3 ? vec3(p[0], p[1], p[2]) : vec3(p[0]);
}

// A 1- or 2-channel image keeps the luminance: the scalar the rest of the tool would use.
void Image::set_rgb(int x, int y, vec3 v) {
  float* p = &data[(size_t(y) * width + x) * channels];
  if (channels >= 3) {
    p[0] = v.x;
    p[1] = v.y;
    p[2] = v.z;
  } else {
    p[0] = luminance(v);
  }
}

float srgb_encode(float linear) {
  if (linear <= 0.0031308f) return 12.92f * linear;
  // The affine step in double: in float, 1.055f - 0.055f is 0.99999994 and white would not be 1.
  return float(1.055 * double(std::pow(linear, 1.0f / 2.4f)) - 0.055);
}

float srgb_decode(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow(float((double(encoded) + 0.055) / 1.055), 2.4f);
}

// Non-finite values display as 0 (black), the same value write_image stores for them.
Image to_display(const Image& linear, float exposure) {
  Image out = linear;
  const float scale = std::exp2(exposure);
  for_each_value(out,
                 [scale](float v) { return srgb_encode(std::clamp(finite_or_zero(v * scale), 0.0f, 1.0f)); });
  return out;
}

Image from_display(const Image& display) {
  Image out = display;
  for_each_value(out, [](float v) { return srgb_decode(finite_or_zero(v)); });
  return out;
}

void write_image(const std::string& path, const Image& rgb, const std::vector<Layer>& layers,
                 float exposure, ExrValues exr_values) {
  const FileFormat format = format_for(path);
  check_writable(path, rgb, layers);
  // The temporary below is renamed over the target, which must therefore not be a device or FIFO.
  if (!write_via_rename(path)) throw Error("cannot write image " + path + ": not a regular file");
  const fs::path target(path);
  if (target.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw Error("cannot write image " + path + ": cannot create its folder (" + ec.message() + ")");
  }
  const fs::path temp = temp_path_for(target);
  TempFile guard(temp.string());  // a SIGINT during the write leaves no temporary beside the output
  switch (format) {
    case FileFormat::exr: {
      Pixels px = pack_float(rgb, layers);
      px.spec.attribute("compression", "zip");
      if (exr_values == ExrValues::float16) {
        // Beyond the largest half a value would become infinite.
        for (float& v : px.floats) v = std::clamp(v, -65504.0f, 65504.0f);
        px.spec.set_format(OIIO::TypeDesc::HALF);
      }
      write_with_oiio(temp, path, px);
      break;
    }
    case FileFormat::hdr:
      write_with_oiio(temp, path, pack_float(rgb, {}));
      break;
    case FileFormat::png:
      write_with_oiio(temp, path, pack_display(rgb, exposure));
      break;
  }
  guard.release();  // renamed into place
}

Image read_image_stored(const std::string& path, bool* was_display) {
  QuietStderrForPng quiet(path);
  auto in = open_input(path);
  const std::vector<float> values = read_all_channels(*in, path);
  if (was_display) *was_display = is_display_encoded(*in);
  return gather(in->spec(), values, rgb_channels(in->spec()));
}

Image read_image(const std::string& path, bool* was_display) {
  bool display = false;
  Image image = read_image_stored(path, &display);
  if (was_display) *was_display = display;
  if (display)
    for (float& v : image.data) v = srgb_decode(v);
  return image;
}

Image read_layer(const std::string& path, const std::string& layer) {
  QuietStderrForPng quiet(path);
  auto in = open_input(path);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<int> channels;
  const int r = channel_index(spec, layer + ".R"), g = channel_index(spec, layer + ".G"),
            b = channel_index(spec, layer + ".B"), x = channel_index(spec, layer + ".X"),
            y = channel_index(spec, layer + ".Y");
  if (r >= 0 && g >= 0 && b >= 0) {
    channels = {r, g, b};
  } else if (x >= 0 && y >= 0) {
    channels = {x, y};
  } else if (y >= 0) {
    channels = {y};
  } else {
    std::string available;
    for (const std::string& name : layer_names(spec)) available += (available.empty() ? "" : ", ") + name;
    throw Error("image " + path + " has no layer '" + layer + "' (" +
                (available.empty() ? std::string("it has no layers") : "layers: " + available) + ")");
  }
  return gather(spec, read_all_channels(*in, path), channels);
}

std::vector<std::string> list_layers(const std::string& path) {
  return layer_names(open_input(path)->spec());
}

}  // namespace sst
