#include "core/lighttree/sort_key.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <string>

#include "core/util/error.h"

namespace sst {
namespace {

// Spreads the low 10 bits of x so that two zero bits follow each one.
constexpr uint32_t expand_bits_10(uint32_t x) {
  x &= 0x3ffu;
  x = (x * 0x00010001u) & 0xFF0000FFu;
  x = (x * 0x00000101u) & 0x0F00F00Fu;
  x = (x * 0x00000011u) & 0xC30C30C3u;
  x = (x * 0x00000005u) & 0x49249249u;
  return x;
}

// expand_bits_10 of every 10-bit value (4 KiB): three loads per key instead of 12 multiplies.
struct ExpandTable {
  uint32_t bits[1024];
  constexpr ExpandTable() : bits{} {
    for (uint32_t i = 0; i < 1024; ++i) bits[i] = expand_bits_10(i);
  }
};
constexpr ExpandTable kExpand;

// Branch-free clamp; `cell` is never NaN: VPL positions are checked finite and the grid's
// scale is finite.
uint32_t quantize_axis(float p, float origin, float scale) {
  return uint32_t(std::min(std::max((p - origin) * scale, 0.0f), 1023.0f));
}

// Sub-triangles of one level of the 4-way subdivision of a triangle with barycentric
// coordinates (a, b, c): 0, 1, 2 are the corner triangles at x, y, z (the points with that
// coordinate >= 1/2), 3 is the middle (upside-down) one. Its own coordinates are
//   corner k: x' = 2x - [x is coordinate k],   middle: x' = 1 - 2x.
// undivide() maps sub-triangle coordinates back to the parent's.
void undivide(uint32_t sub, float& a, float& b, float& c) {
  switch (sub) {
    case 0: a = 0.5f * (a + 1.0f); b *= 0.5f; c *= 0.5f; break;
    case 1: a *= 0.5f; b = 0.5f * (b + 1.0f); c *= 0.5f; break;
    case 2: a *= 0.5f; b *= 0.5f; c = 0.5f * (c + 1.0f); break;
    default: a = 0.5f * (1.0f - a); b = 0.5f * (1.0f - b); c = 0.5f * (1.0f - c); break;
  }
}

constexpr int kSubdivisionLevels = 3;

std::string vpl_problem(const Vpl& v) {
  if (!is_finite(v.position)) return "position is not finite";
  if (!is_finite(v.normal) || glm::dot(v.normal, v.normal) == 0.0f) return "normal is zero or not finite";
  if (!is_finite(v.intensity) || v.intensity.x < 0.0f || v.intensity.y < 0.0f || v.intensity.z < 0.0f)
    return "intensity is negative or not finite";
  return {};
}

bool vpl_ok(const Vpl& v) {
  return is_finite(v.position) && is_finite(v.normal) && glm::dot(v.normal, v.normal) > 0.0f &&
         is_finite(v.intensity) && v.intensity.x >= 0.0f && v.intensity.y >= 0.0f && v.intensity.z >= 0.0f;
}

}  // namespace

uint32_t morton_code(uint32_t x, uint32_t y, uint32_t z) {
  return (kExpand.bits[x & 1023u] << 2) | (kExpand.bits[y & 1023u] << 1) | kExpand.bits[z & 1023u];
}

MortonGrid MortonGrid::over(const Bounds3& bounds) {
  MortonGrid grid;
  if (bounds.empty()) return grid;
  grid.origin = bounds.lo;
  vec3 extent = bounds.hi - bounds.lo;
  for (int axis = 0; axis < 3; ++axis) {
    float s = extent[axis] > 0.0f ? 1024.0f / extent[axis] : 0.0f;
    // A denormal extent would overflow the scale; such an axis counts as degenerate.
    grid.scale[axis] = std::isfinite(s) ? s : 0.0f;
  }
  return grid;
}

uint32_t MortonGrid::code(vec3 p) const {
  return morton_code(quantize_axis(p.x, origin.x, scale.x), quantize_axis(p.y, origin.y, scale.y),
                     quantize_axis(p.z, origin.z, scale.z));
}

uint32_t quantize_normal(vec3 n) {
  uint32_t code = (n.x < 0.0f ? 4u : 0u) | (n.y < 0.0f ? 2u : 0u) | (n.z < 0.0f ? 1u : 0u);
  // Central projection onto the octant's triangle |x| + |y| + |z| = 1 gives barycentric
  // coordinates (a, b, c) directly.
  vec3 m(std::fabs(n.x), std::fabs(n.y), std::fabs(n.z));  // glm::abs compiles to branches
  float sum = m.x + m.y + m.z;
  if (!(sum > 0.0f) || !std::isfinite(sum)) m = vec3(1.0f), sum = 3.0f;
  // Three levels of subdivision make a grid of the lines a, b, c = i / 8, so the cell is known
  // from (floor(8a), floor(8b), floor(8c)) alone. Level by level from the top bit: coordinate
  // x is >= 1/2 in the current triangle iff its bit is set; a corner triangle keeps the lower
  // bits (x' = 2x - 1 or 2x), the middle one complements them (x' = 1 - 2x). Integer bit
  // arithmetic instead of the float comparisons of the recursive definition: random normals
  // mispredict those branches, which made this the most expensive part of a key.
  float scale = 8.0f / sum;
  uint32_t i = std::min(uint32_t(m.x * scale), 7u), j = std::min(uint32_t(m.y * scale), 7u),
           k = std::min(uint32_t(m.z * scale), 7u);
  uint32_t flip = 0;
  for (int level = kSubdivisionLevels - 1; level >= 0; --level) {
    uint32_t ta = ((i >> level) ^ flip) & 1u, tb = ((j >> level) ^ flip) & 1u, tc = ((k >> level) ^ flip) & 1u;
    // At most one coordinate is >= 1/2 but for rounding on a border; then x wins over y over z.
    uint32_t corner_b = (ta ^ 1u) & tb, corner_c = (ta ^ 1u) & (tb ^ 1u) & tc;
    uint32_t middle = (ta | tb | tc) ^ 1u;
    code = (code << 2) | (corner_b + 2u * corner_c + 3u * middle);
    flip ^= middle;
  }
  return code;
}

vec3 decode_normal(uint32_t code) {
  float a = 1.0f / 3.0f, b = 1.0f / 3.0f, c = 1.0f / 3.0f;
  for (int level = 0; level < kSubdivisionLevels; ++level) undivide((code >> (2 * level)) & 3u, a, b, c);
  uint32_t octant = (code >> (2 * kSubdivisionLevels)) & 7u;
  vec3 n((octant & 4u) ? -a : a, (octant & 2u) ? -b : b, (octant & 1u) ? -c : c);
  return glm::normalize(n);
}

Bounds3 compute_vpl_bounds(const VplSet& vpls) {
  struct Partial {
    Bounds3 bounds;
    size_t first_bad = SIZE_MAX;
  };
  Partial total = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, vpls.size(), 4096), Partial{},
      [&](const tbb::blocked_range<size_t>& r, Partial part) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const Vpl& v = vpls[i];
          if (!vpl_ok(v)) {
            part.first_bad = std::min(part.first_bad, i);
            continue;
          }
          part.bounds.extend(v.position);
        }
        return part;
      },
      [](Partial x, const Partial& y) {
        x.bounds.extend(y.bounds);
        x.first_bad = std::min(x.first_bad, y.first_bad);
        return x;
      });
  if (total.first_bad != SIZE_MAX)
    throw Error("light tree: vpl " + std::to_string(total.first_bad) + ": " + vpl_problem(vpls[total.first_bad]));
  return total.bounds;
}

void check_sort_key_capacity(size_t vpl_count) {
  if (vpl_count > kMaxSortKeyVpls)
    throw Error("light tree: " + std::to_string(vpl_count) + " VPLs exceed the sort key's limit of " +
                std::to_string(kMaxSortKeyVpls) + " (25 id bits)");
}

void compute_sort_keys(const VplSet& vpls, const Bounds3& vpl_bounds, std::vector<uint64_t>& keys,
                       std::vector<uint32_t>& ids) {
  check_sort_key_capacity(vpls.size());
  keys.resize(vpls.size());
  ids.resize(vpls.size());
  MortonGrid grid = MortonGrid::over(vpl_bounds);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, vpls.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      keys[i] = make_sort_key(grid.code(vpls[i].position), quantize_normal(vpls[i].normal), uint32_t(i));
      ids[i] = uint32_t(i);
    }
  });
}

}  // namespace sst
