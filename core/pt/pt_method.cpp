#include "core/pt/pt_method.h"

#include "core/pt/path_tracer.h"

namespace sst {

MethodInfo pt_method_info() {
  return method_info<PathTracerParams>(
      "pt",
      "unidirectional path tracer: next-event estimation with MIS (power heuristic), lights picked by power, close "
      "emissive triangles sampled by solid angle and others by area; the ground truth (PT_n = --max-bounces n)",
      [](const PathTracerParams& p) -> std::unique_ptr<Method> { return std::make_unique<PathTracer>(p); });
}

}  // namespace sst
