// The VPL singularity clamp relative to the VPLs' bounds (VplParams::clamp_relative_to =
// vpl_bounds, docs/design/lengths.md): a VPL's 1/d^2 is bounded by 1/c^2 with c = fraction * D for
// the whole frame. D is the diagonal of the VPLs' bounding box, the extent of what is lit; a
// sunlit ground outside a room still makes it hundreds of times the room's, which is why the
// default clamp follows the camera distance instead (vpl_clamp_at, vpl_shading.h). The scene's
// diagonal is used only when the VPLs span no extent (one VPL, or all at one point), where a
// VPL-derived D would be 0 and the clamp would vanish.
#pragma once
#include "core/math/math.h"
#include "core/scene/scene.h"
#include "core/vpl/vpl.h"

namespace sst {

Bounds3 vpl_bounds(const VplSet& vpls);
// c = clamp_fraction * D, D as above; 0 for an empty set in an empty scene.
float vpl_clamp_distance(float clamp_fraction, const VplSet& vpls, const Scene& scene);

}  // namespace sst
