#include "core/vpl/vpl_ply.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "core/util/error.h"
#include "core/util/json_io.h"

namespace sst {
namespace {
static_assert(std::endian::native == std::endian::little, "PLY output assumes a little-endian host");

constexpr const char* kFloatNames[9] = {"x", "y", "z", "nx", "ny", "nz", "r", "g", "b"};

void append_bytes(std::string& out, const void* p, size_t n) { out.append(static_cast<const char*>(p), n); }

// x / (x + mean), then a 1/2.2 gamma: bright VPLs saturate gently, dim ones stay visible.
uint8_t display_channel(float x, float mean) {
  float t = mean > 0.0f && x > 0.0f ? x / (x + mean) : 0.0f;
  return uint8_t(std::lround(255.0f * std::pow(std::clamp(t, 0.0f, 1.0f), 1.0f / 2.2f)));
}

float mean_luminance(const VplSet& vpls) {
  double sum = 0.0;
  for (const Vpl& v : vpls) sum += luminance(v.intensity);
  return vpls.empty() ? 0.0f : float(sum / double(vpls.size()));
}

size_t type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

struct Layout {
  size_t count = 0;
  size_t stride = 0;
  int offset[9] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};  // of each of kFloatNames
};

// Parses the header up to end_header; `in` is left at the first data byte.
Layout read_header(std::istream& in, const std::string& path) {
  auto fail = [&](const std::string& why) { return Error(path + ": not a VPL PLY file (" + why + ")"); };
  std::string line;
  if (!std::getline(in, line) || line != "ply") throw fail("no 'ply' magic");
  Layout layout;
  bool format_ok = false, in_vertex = false, seen_vertex = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "end_header") {
      if (!format_ok) throw fail("not binary_little_endian 1.0");
      if (!seen_vertex) throw fail("no vertex element");
      for (int i = 0; i < 9; ++i)
        if (layout.offset[i] < 0) throw fail(std::string("no float property '") + kFloatNames[i] + "'");
      return layout;
    }
    if (key == "format") {
      std::string format, version;
      words >> format >> version;
      format_ok = format == "binary_little_endian" && version == "1.0";
    } else if (key == "element") {
      std::string name;
      words >> name;
      if (seen_vertex) throw fail("elements after 'vertex' are not supported");
      in_vertex = name == "vertex";
      if (!in_vertex) throw fail("element '" + name + "' before 'vertex'");
      seen_vertex = true;
      if (!(words >> layout.count)) throw fail("bad vertex count");
    } else if (key == "property") {
      if (!in_vertex) throw fail("property outside the vertex element");
      std::string type, name;
      words >> type >> name;
      if (type == "list") throw fail("list properties are not supported");
      size_t size = type_size(type);
      if (size == 0) throw fail("unknown property type '" + type + "'");
      for (int i = 0; i < 9; ++i) {
        if (name != kFloatNames[i]) continue;
        if (size != 4 || (type != "float" && type != "float32")) throw fail("property '" + name + "' is not float");
        layout.offset[i] = int(layout.stride);
      }
      layout.stride += size;
    } else if (key != "comment" && key != "obj_info" && !key.empty()) {
      throw fail("unexpected header line '" + line + "'");
    }
  }
  throw fail("no end_header");
}
}  // namespace

void write_vpls_ply(const std::string& path, const VplSet& vpls) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\n"
      "comment sst virtual point lights: position, unit normal, intensity r g b (W/sr per channel)\n"
      "element vertex " + std::to_string(vpls.size()) + "\n";
  for (const char* name : kFloatNames) out += std::string("property float ") + name + "\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  const size_t header = out.size();
  out.reserve(header + vpls.size() * (9 * sizeof(float) + 3));
  const float mean = mean_luminance(vpls);
  for (const Vpl& v : vpls) {
    float f[9] = {v.position.x, v.position.y, v.position.z, v.normal.x,   v.normal.y,
                  v.normal.z,   v.intensity.x, v.intensity.y, v.intensity.z};
    append_bytes(out, f, sizeof f);
    uint8_t c[3] = {display_channel(v.intensity.x, mean), display_channel(v.intensity.y, mean),
                    display_channel(v.intensity.z, mean)};
    append_bytes(out, c, sizeof c);
  }
  write_text_atomic(path, out);
}

VplSet read_vpls_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path);
  Layout layout = read_header(in, path);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (layout.stride == 0 || data.size() / layout.stride < layout.count)
    throw Error(path + ": truncated (" + std::to_string(layout.count) + " vertices announced)");
  VplSet vpls(layout.count);
  for (size_t i = 0; i < layout.count; ++i) {
    float f[9];
    for (int k = 0; k < 9; ++k) std::memcpy(&f[k], data.data() + i * layout.stride + size_t(layout.offset[k]), 4);
    vpls[i].position = vec3(f[0], f[1], f[2]);
    vpls[i].normal = vec3(f[3], f[4], f[5]);
    vpls[i].intensity = vec3(f[6], f[7], f[8]);
  }
  return vpls;
}

}  // namespace sst
