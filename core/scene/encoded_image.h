// What the header of an encoded PNG or JPEG texture says, read before any decoder sees the bytes.
// stb_image (which decodes glTF textures, through tinygltf) allocates whatever size a header
// declares, so a few hundred bytes can ask for gigabytes, and its JPEG reader in Debian 12
// (v2.27) indexes past its Huffman tables when a DHT segment declares more than 256 codes (fixed
// upstream in v2.28). Both are refused here, with a reason, instead.
#pragma once
#include <cstddef>
#include <string>

namespace sst {

struct EncodedImageHeader {
  int width = 0, height = 0;
  int channels = 0;        // as stored (1..4)
  int bytes_per_channel = 1;
};

// Reads the header of a PNG (IHDR) or JPEG (SOF marker, after checking every DHT segment before
// it and between scans). Returns "" and fills `header`, or why the bytes cannot be decoded safely.
std::string read_encoded_image_header(const unsigned char* bytes, size_t size, EncodedImageHeader& header);

}  // namespace sst
