// The interface every many-light method implements: given the frame's VPLs (and whatever it
// builds from them in prepare: a light tree, per-block cuts), estimate the indirect light at one
// shading point. ManyLightMethod (many_light_method.h) does everything around it: VPL
// generation, camera rays, direct light, accumulation, AOVs, counters, timings.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/material/brdf.h"
#include "core/render/method.h"
#include "core/rng/sobol_sampler.h"
#include "core/util/error.h"
#include "core/vpl/vpl.h"

namespace sst {

struct GpuSamplerInputs;  // core/manylight/gpu_sampler_inputs.h
struct LightTree;
struct LightTreeParams;
struct LightTreeBuildStats;

// Builds a frame's light tree as build_light_tree does, possibly elsewhere (the Vulkan backend's
// GPU builder); sets *built_on to where it ran ("cpu" or "gpu").
using LightTreeBuildFn = std::function<LightTree(const VplSet& vpls, const LightTreeParams& params,
                                                 const Bounds3* scene_bounds, LightTreeBuildStats* stats,
                                                 std::string* built_on)>;

// A camera ray's first hit, ready to shade.
struct ShadingPoint {
  vec3 p{0.0f};
  vec3 ng{0.0f};  // geometric normal on the viewer's side
  Basis basis;    // shading basis (basis.n = shading normal)
  vec3 wo{0.0f};  // toward the viewer, in the shading basis
  Brdf brdf;
  int x = 0, y = 0;  // pixel
};

// The first hit `s` of a camera ray along `ray_direction` through pixel (x, y), ready to shade
// (many_light_method.cpp; gpu/shaders/many_light.comp builds the same on the GPU).
struct Surface;
ShadingPoint shading_point(const Surface& s, vec3 ray_direction, bool diffuse_only, int x, int y);

// The frame-wide inputs of sampling.
struct ManyLightFrame {
  const RenderContext& context;
  const VplSet& vpls;
  float clamp_distance;  // singularity clamp c (vpl_clamp.h)
};

struct IndirectEstimate {
  vec3 value{0.0f};          // an estimate of sum_j contribution_j * visibility_j
  uint32_t nodes_visited = 0;  // tree nodes visited to draw the sample(s)
  uint32_t shadow_rays = 0;
};

class IndirectSampler {
 public:
  virtual ~IndirectSampler() = default;
  // Per-frame preparation (tree build, cuts); `counters` receives method-specific counters.
  virtual void prepare(const ManyLightFrame& frame, StageTimer& timer, nlohmann::json& counters) {}
  // One indirect sample at `point`; thread-safe (called from many threads at once).
  virtual IndirectEstimate estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                    PixelSampler& sampler) const = 0;
  // Replaces how prepare() builds the frame's tree (samplers without a tree ignore it); an empty
  // function restores the CPU builder.
  virtual void set_tree_builder(LightTreeBuildFn builder) {}
  // The GPU twin of the state prepare() built (gpu_sampler_inputs.h): the method id and
  // parameters, and views of the tree, cuts and mock cut, for the Vulkan backend to upload and
  // gpu/shaders/indirect_sampler.glsl to run estimate() with. Call after prepare(frame). A
  // sampler without a GPU twin keeps this default, which throws sst::Error.
  virtual void gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
    throw Error("this sampler has no Vulkan port; use --backend cpu");
  }
};

}  // namespace sst
