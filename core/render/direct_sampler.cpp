#include "core/render/direct_sampler.h"

#include <cmath>

#include "core/util/error.h"

namespace sst {

const char* direct_sampler_names() { return "nee, restir"; }

void validate(const RestirDiParams& p) {
  if (p.candidates < 1 || p.candidates > 1024)
    throw Error("restir_candidates must be in 1..1024 (got " + std::to_string(p.candidates) + ")");
  if (p.brdf_candidates < 0 || p.brdf_candidates > 1)
    throw Error("restir_brdf_candidates must be 0 or 1 (got " + std::to_string(p.brdf_candidates) + ")");
  if (!(p.temporal_cap > 0.0f && p.temporal_cap <= 1000.0f))
    throw Error("restir_temporal_cap must be in (0, 1000] (got " + std::to_string(p.temporal_cap) + ")");
  if (p.spatial_passes < 0 || p.spatial_passes > 8)
    throw Error("restir_spatial_passes must be in 0..8 (got " + std::to_string(p.spatial_passes) + ")");
  if (p.neighbours < 1 || p.neighbours > 16)
    throw Error("restir_neighbours must be in 1..16 (got " + std::to_string(p.neighbours) + ")");
  if (!(p.radius >= 1.0f && p.radius <= 256.0f) || !std::isfinite(p.radius))
    throw Error("restir_radius must be in 1..256 pixels (got " + std::to_string(p.radius) + ")");
  if (p.combine != "unbiased" && p.combine != "biased")
    throw Error("unknown restir_combine '" + p.combine + "' (valid: unbiased, biased)");
}

}  // namespace sst
