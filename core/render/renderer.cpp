#include "core/render/renderer.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <memory>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/render/backend.h"
#include "core/render/camera.h"
#include "core/render/method_registry.h"

namespace sst {

RenderResult render_frame(const Scene& scene, const RenderOptions& options, const nlohmann::json& method_params,
                          bool quiet) {
  RenderResult result;
  result.options = options;
  validate(result.options);
  // The backend that runs ("auto" becomes a concrete one; "vulkan" fails with one line until issue 5).
  std::string backend_note;
  result.options.backend = resolve_backend(options.backend, 0, &backend_note);
  if (!backend_note.empty() && !quiet) std::fprintf(stderr, "note: %s\n", backend_note.c_str());
  // Create the method first: a bad parameter fails before any expensive work.
  std::unique_ptr<Method> method = create_method(options.method, method_params);
  result.method_params = method->params();

  std::unique_ptr<tbb::global_control> threads;
  if (options.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

  const Camera& camera = select_camera(scene, options.camera);
  resolve_resolution(camera, result.options.width, result.options.height);
  validate(result.options);
  auto accel = result.timer.time("accel_build", [&] { return std::make_unique<EmbreeAccel>(scene); });
  auto lights = result.timer.time("light_setup", [&] { return std::make_unique<LightSampler>(scene); });
  PinholeCamera pinhole(camera, result.options.width, result.options.height);
  RenderContext context{scene, *accel, *lights, pinhole, result.options, result.options.width, result.options.height, quiet};
  result.frame = method->render(context, result.timer);
  return result;
}

}  // namespace sst
