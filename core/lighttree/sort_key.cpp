#include "core/lighttree/sort_key.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <string>

#include "core/util/error.h"

namespace sst {
namespace {

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

vec3 decode_normal(uint32_t code) {
  float a = 1.0f / 3.0f, b = 1.0f / 3.0f, c = 1.0f / 3.0f;
  for (int level = 0; level < kNormalSubdivisionLevels; ++level) undivide((code >> (2 * level)) & 3u, a, b, c);
  uint32_t octant = (code >> (2 * kNormalSubdivisionLevels)) & 7u;
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

void compute_sort_keys(const VplSet& vpls, const Bounds3& vpl_bounds, std::vector<uint64_t>& keys) {
  check_sort_key_capacity(vpls.size());
  keys.resize(vpls.size());
  MortonGrid grid = MortonGrid::over(vpl_bounds);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, vpls.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      keys[i] = sort_key_from_words(vpl_sort_key(vpls[i].position, vpls[i].normal, uint32_t(i), grid.origin, grid.scale));
    }
  });
}

}  // namespace sst
