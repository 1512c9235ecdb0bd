#include "core/scene/encoded_image.h"

#include <cstdint>
#include <cstring>

namespace sst {
namespace {

uint32_t big_endian32(const unsigned char* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }
int big_endian16(const unsigned char* p) { return p[0] << 8 | p[1]; }

std::string png_header(const unsigned char* p, size_t n, EncodedImageHeader& h) {
  // Signature (8), IHDR length (4) and type (4), then width, height, bit depth, colour type.
  if (n < 8 + 8 + 13 || std::memcmp(p + 12, "IHDR", 4) != 0) return "PNG without an IHDR header";
  uint32_t w = big_endian32(p + 16), h32 = big_endian32(p + 20);
  if (w == 0 || h32 == 0 || w > 0x7fffffffu || h32 > 0x7fffffffu) return "PNG of impossible size " + std::to_string(w) + "x" + std::to_string(h32);
  h.width = int(w);
  h.height = int(h32);
  h.bytes_per_channel = p[24] == 16 ? 2 : 1;
  switch (p[25]) {
    case 0: h.channels = 1; break;  // grey
    case 2: h.channels = 3; break;  // RGB
    case 3: h.channels = 4; break;  // palette (expanded; alpha possible)
    case 4: h.channels = 2; break;  // grey + alpha
    case 6: h.channels = 4; break;  // RGBA
    default: return "PNG of unknown colour type " + std::to_string(p[25]);
  }
  return "";
}

// One DHT segment (without its marker and length): each table's 16 code counts must add up to at
// most 256 symbols and form a prefix code (the Kraft inequality), as the JPEG standard requires.
std::string check_huffman_tables(const unsigned char* p, size_t n) {
  size_t i = 0;
  while (i < n) {
    if (n - i < 17) return "corrupt JPEG: truncated Huffman table";
    int kind = p[i] >> 4, id = p[i] & 15;
    if (kind > 1 || id > 3) return "corrupt JPEG: Huffman table of unknown class or id";
    int symbols = 0;
    unsigned code = 0;  // codes of the current length, canonical order
    for (int length = 1; length <= 16; ++length) {
      int count = p[i + length];
      symbols += count;
      code = (code << 1) + unsigned(count);
      if (code > (1u << length)) return "corrupt JPEG: Huffman code lengths are not a prefix code";
    }
    if (symbols > 256) return "corrupt JPEG: Huffman table of " + std::to_string(symbols) + " symbols (at most 256)";
    i += 17 + size_t(symbols);
  }
  return i == n ? "" : "corrupt JPEG: Huffman table longer than its segment";
}

std::string jpeg_header(const unsigned char* p, size_t n, EncodedImageHeader& h) {
  size_t i = 2;  // after SOI
  bool found = false;
  while (i + 1 < n) {
    if (p[i] != 0xFF) return "corrupt JPEG: expected a marker at byte " + std::to_string(i);
    while (i + 1 < n && p[i + 1] == 0xFF) ++i;  // fill bytes
    if (i + 1 >= n) break;
    unsigned char marker = p[i + 1];
    i += 2;
    if (marker == 0xD9) break;                                     // EOI
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    if (n - i < 2) return "corrupt JPEG: truncated segment";
    size_t length = size_t(big_endian16(p + i));
    if (length < 2 || length > n - i) return "corrupt JPEG: segment longer than the file";
    const unsigned char* body = p + i + 2;
    size_t body_size = length - 2;
    if (marker == 0xC4) {
      if (std::string why = check_huffman_tables(body, body_size); !why.empty()) return why;
    } else if ((marker >= 0xC0 && marker <= 0xCF) && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
      if (body_size < 6) return "corrupt JPEG: truncated frame header";
      h.height = big_endian16(body + 1);
      h.width = big_endian16(body + 3);
      h.channels = body[5];
      h.bytes_per_channel = 1;
      if (h.width == 0 || h.height == 0 || h.channels < 1 || h.channels > 4)
        return "JPEG of unsupported size or channels (" + std::to_string(h.width) + "x" + std::to_string(h.height) + ", " +
               std::to_string(h.channels) + " channels)";
      found = true;
    }
    i += length;
    if (marker == 0xDA) {
      // Entropy-coded data up to the next marker that is not a stuffed zero or a restart.
      while (i + 1 < n && !(p[i] == 0xFF && p[i + 1] != 0x00 && !(p[i + 1] >= 0xD0 && p[i + 1] <= 0xD7))) ++i;
    }
  }
  return found ? "" : "corrupt JPEG: no frame header";
}

}  // namespace

std::string read_encoded_image_header(const unsigned char* bytes, size_t size, EncodedImageHeader& header) {
  header = {};
  if (size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0) return png_header(bytes, size, header);
  if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return jpeg_header(bytes, size, header);
  return "neither PNG nor JPEG";
}

}  // namespace sst
