// The push constants of the filter dispatches, defined once for C++ (namespace sst::glsl,
// static_asserts) and GLSL. The host fills them from the parameter structs (filter_params.h) once
// per dispatch, folding each level's constants in, so that both backends divide by the same floats.
#ifndef SST_CORE_FILTER_FILTER_LAYOUT_H
#define SST_CORE_FILTER_FILTER_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace sst::glsl {
using uint = uint32_t;
#endif

// One level of the edge-avoiding a-trous filter (Dammertz et al. 2010).
struct AtrousPush {
  uint width;
  uint height;
  uint step;         // 2^level: the spacing of the kernel's taps
  uint pad0;
  float inv_color;   // 1 / (sigma_color^2 2^-level): the colour weight tightens level by level
  float inv_normal;  // 1 / (sigma_normal^2 step^2)
  float inv_depth;   // 1 / sigma_depth^2
  float pad1;
};

// One dispatch of SVGF's spatial filter: the variance estimate (SVGF_PASS_VARIANCE) or one a-trous
// level (SVGF_PASS_ATROUS).
#define SVGF_PASS_VARIANCE 0u
#define SVGF_PASS_ATROUS 1u
struct SvgfPush {
  uint width;
  uint height;
  uint step;  // 2^level
  uint pass;
  float sigma_z;
  float sigma_n;
  float sigma_l;
  float min_history;  // history length from which the temporal moments give the variance
};

// Joint bilateral upsampling of a low-resolution image to width x height.
struct UpsamplePush {
  uint width;
  uint height;
  uint low_width;
  uint low_height;
  uint pad1;
  float n_min;
  float d_max;  // relative to the full-resolution pixel's depth
  uint pad0;
};

#ifdef __cplusplus
static_assert(sizeof(AtrousPush) == 32 && offsetof(AtrousPush, inv_color) == 16);
static_assert(sizeof(SvgfPush) == 32 && offsetof(SvgfPush, sigma_z) == 16);
static_assert(sizeof(UpsamplePush) == 32 && offsetof(UpsamplePush, n_min) == 20);
}  // namespace sst::glsl
#endif

#endif  // SST_CORE_FILTER_FILTER_LAYOUT_H
