// `pt`: unidirectional path tracer with next-event estimation and MIS (power heuristic) between
// light sampling and BRDF sampling. `max_bounces` counts indirect bounces, as Cycles and the SST
// paper's PT_n rows do: 0 = direct light only. It is the ground truth of every other method.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/method.h"
#include "core/shading/surface.h"
#include "core/rng/sobol_sampler.h"
#include "core/util/params.h"
// The path itself, shared with the GPU, bound to the Scene, LightSampler::packed() and EmbreeAccel.
#include "core/pt/trace_path.h"

namespace sst {

struct PathTracerParams {
  int max_bounces = 8;
  int rr_min_bounces = 3;

  template <class V>
  void visit(V&& v) {
    v("max_bounces", max_bounces,
      "maximum number of indirect bounces, as Cycles counts them (0: direct light only; the SST paper's PT1, PT2, "
      "PT3 are 1, 2, 3)");
    v("rr_min_bounces", rr_min_bounces,
      "indirect bounces before Russian roulette may end a path (none, if >= max_bounces)");
  }
};

// The path PathTracer traces for these options: vertex 1 gathers no light under ReSTIR DI
// (restir_direct), whose pass adds the first hit's direct light (path_direct_elsewhere).
PathConfig path_tracer_config(const PathTracerParams& params, const RenderOptions& options);

// `first_hit`, when given, receives the surface the camera ray hit (valid when the returned
// depth is > 0): the many-light methods shade it with their own indirect estimate after taking
// the direct light from here (max_bounces = 0), so direct light is computed one way for all.
PathSample trace_path(const RenderContext& context, const PathTracerParams& params, Ray ray, PixelSampler& sampler,
                      RayCounters& counters, Surface* first_hit = nullptr);

// Pixel (x, y) of `frame` from the sums of its samples' PathSamples (inv_spp = 1 / spp): the
// layers' means and the normalised normal. The GPU's passes write their sums through it too.
void write_path_means(const PathSample& sum, float inv_spp, int x, int y, FrameOutput& frame);

class PathTracer final : public Method {
 public:
  explicit PathTracer(const PathTracerParams& params);
  FrameOutput render(const RenderContext& context, StageTimer& timer) override;
  nlohmann::json params() const override;
  const PathTracerParams& tracer_params() const { return params_; }

 private:
  PathTracerParams params_;
};

}  // namespace sst
