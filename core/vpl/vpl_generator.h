// Instant-radiosity VPL generation (Keller 1997; docs/design/methods.md): light paths leave the lights
// (LightSampler::sample_emission) and deposit a VPL at every diffuse surface they hit, with
// intensity = throughput * albedo / pi, then bounce on, cosine-weighted. Parameters: VplParams.
//
// Path count. Path i is core/vpl/light_path.h's trace_light_path(seed, i), a pure function of
// (seed, i). Paths 0, 1, 2, ... are traced until `vpls` VPLs exist; the last path's surplus VPLs
// are dropped, so the set has exactly `vpls` VPLs (fewer only when the scene cannot produce
// them: see kMaxPathsPerVpl). Every intensity is divided by P, the number of paths traced up to
// and including the last one used, escaped and empty paths included. P is a stopping time, which
// makes the estimate consistent with a bias of order 1/P (none at all when every path deposits
// the same number of VPLs, e.g. a closed box without roulette); an exact count keeps tables "at
// N VPLs" honest. The result does not depend on the thread count or the batching.
//
// What is deposited. Both sides of every surface receive VPLs, single-sided materials included,
// because the path tracer shades both sides (only emission is one-sided): the VPL's normal is the
// shading normal turned to the side the light came from. Black surfaces (zero diffuse albedo)
// deposit nothing and end the path: a zero-intensity VPL would only cost shading time.
// In full-BRDF mode the albedo is the diffuse part (1 - metallic) * baseColor (textures applied);
// the specular lobe is not followed, so light reaching diffuse surfaces via a glossy bounce is not
// represented (as in the papers). diffuse_only uses baseColor.
// With interpolated (shading) normals, the adjoint shading-normal correction of light tracing is
// not applied: exact for flat-shaded geometry, a small bias on smooth-shaded meshes.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"
#include "core/util/params.h"
#include "core/vpl/vpl.h"

namespace sst {

// A scene that deposits fewer than one VPL per this many paths (everything black, or lights
// that miss the geometry) stops here with fewer VPLs than asked for, instead of tracing forever.
inline constexpr uint64_t kMaxPathsPerVpl = 64;

struct VplParams {
  std::string vpl_source = "paths";
  int vpls = 100000;
  int vpl_max_bounces = 8;
  int vpl_min_bounces = 3;
  float clamp_fraction = 0.1f;
  std::string clamp_relative_to = "camera_distance";
  bool clamp_compensation = true;
  float directional_focus = 2.0f;
  float focus_bounces = 0.5f;
  int brsm_resolution = 256;
  float brsm_texels_per_vpl = 1.0f;
  int brsm_maps = 8;
  float brsm_gbuffer_scale = 0.25f;
  int brsm_gbuffer_samples = 8;
  int brsm_screen_samples = 8;
  float brsm_radius = 0.25f;
  bool brsm_filter = true;
  float brsm_power_fraction = 0.01f;
  std::string export_vpls;

  template <class V>
  void visit(V&& v) {
    v("vpl_source", vpl_source,
      "where the VPLs come from: paths (instant-radiosity light paths, every bounce) or brsm (one bidirectional "
      "reflective shadow map per light, the hybrid thesis's: one-bounce VPLs drawn where the camera will see their "
      "light; docs/design/brsm.md)");
    v("vpls", vpls,
      "number of virtual point lights: light paths are traced in order until exactly this many are deposited");
    v("vpl_max_bounces", vpl_max_bounces, "surface hits per light path that deposit a VPL (1: one-bounce GI)");
    v("vpl_min_bounces", vpl_min_bounces,
      "light-path hits before Russian roulette may end a path (survival probability: the largest albedo component)");
    v("clamp_fraction", clamp_fraction,
      "VPL singularity clamp: a VPL's 1/d^2 is at most 1/c^2, c = clamp_fraction x the length of clamp_relative_to");
    v("clamp_relative_to", clamp_relative_to,
      "the length c is a fraction of: camera_distance (the shaded point's distance to the camera, so that geometry "
      "outside the view changes nothing) or vpl_bounds (the diagonal of the VPLs' bounding box, one c for the frame, "
      "as sst did before)");
    v("clamp_compensation", clamp_compensation,
      "add back what the clamp removes (Kollig and Keller 2004): a BRDF-sampled path from the first hit whose first "
      "bounce lands closer than c, weighted by 1 - d^2/c^2 (unbiased); false: the papers' clamped, darkened "
      "estimate");
    v("directional_focus", directional_focus,
      "directional lights start half of their light paths on a disc around the camera of this many times the median "
      "distance to what it sees, the rest on discs 4x, 16x, ... as wide and the whole scene's (unbiased either way; 0: "
      "the whole scene's only, as before), so a sunlit room inside a large landscape still gets VPLs");
    v("focus_bounces", focus_bounces,
      "a light path's bounce from a surface farther from the camera than directional_focus x the median view "
      "distance aims this share of its directions at the sphere of that radius about the camera, the rest "
      "cosine-weighted (unbiased; in [0, 1); 0: every bounce cosine-weighted, as before), so that the light of far "
      "ground reaches the view by many paths rather than a few heavy ones; needs directional_focus > 0");
    v("brsm_resolution", brsm_resolution,
      "brsm: texels per side of each map (a power of two, 2..4096; 0: from the VPL count, brsm_texels_per_vpl): one "
      "light ray and one potential VPL per texel");
    v("brsm_texels_per_vpl", brsm_texels_per_vpl,
      "brsm with brsm_resolution 0: the maps' side is the smallest power of two (16..4096) whose texels number at "
      "least this many per VPL of the map that draws the most (on two CPU cores at equal time, about 1 was best at "
      "4096 and 16k VPLs, but at 100k 64^2 maps beat the rule's larger ones: results/README.md, 'Map size against "
      "the VPL count')");
    v("brsm_maps", brsm_maps,
      "brsm: the most maps; with more lights, consecutive lights of the power distribution share a map (each map "
      "holds about the same power, and its VPL count is in proportion to the power it holds)");
    v("brsm_gbuffer_scale", brsm_gbuffer_scale,
      "brsm: the camera G-buffer that weighs the potential VPLs, as a fraction of the image's resolution (0..1]");
    v("brsm_gbuffer_samples", brsm_gbuffer_samples,
      "brsm: G-buffer samples per potential VPL, at random directions and 1/r^2-distributed distances around it (0: "
      "weigh by power alone)");
    v("brsm_screen_samples", brsm_screen_samples,
      "brsm: G-buffer pixels per potential VPL drawn uniformly over the screen, whose light is added to the "
      "weight, so that a potential VPL that lights only distant surfaces is weighed too (0: the thesis's weight, "
      "which missed 14% of the staircase's one-bounce light)");
    v("brsm_radius", brsm_radius,
      "brsm: the farthest G-buffer sample from a potential VPL, as a fraction of its distance to the camera; also "
      "the distance below which the filter treats two potential VPLs as one surface");
    v("brsm_filter", brsm_filter,
      "brsm: filter the weights with a 5x5 kernel over similar potential VPLs (normals within 25 degrees, closer "
      "than brsm_radius), the thesis's edge-aware filter");
    v("brsm_power_fraction", brsm_power_fraction,
      "brsm: the share of each map's draws that follows the potential VPLs' power alone instead of their weight, "
      "so that light the weights miss is still drawn and the set stays unbiased (0: the thesis's weights only, "
      "biased where they are 0)");
    v("export_vpls", export_vpls,
      "write the VPL set to this PLY point cloud (position, normal, intensity) after generation (empty: don't)");
  }

  // The surface hits the set's light has made, at most: BRSM's VPLs hold one-bounce light only.
  // The clamp's compensation paths stop there too, so that they add back only what the set holds.
  int light_bounces() const { return vpl_source == "brsm" ? 1 : vpl_max_bounces; }
};

// Throws sst::Error naming the parameter when a value is impossible.
void validate(const VplParams& params);

struct VplStats {
  std::string source = "paths";  // VplParams::vpl_source
  uint64_t paths = 0;          // P: paths the set represents (intensities are divided by it); brsm: texels
  uint64_t pvpls = 0;          // brsm: texels with a potential VPL
  uint64_t maps = 0;           // brsm: maps
  uint32_t resolution = 0;     // brsm: texels per side of each map
  uint64_t paths_traced = 0;   // including paths traced past the last one used
  uint64_t vpls = 0;           // deposited (== the set's size)
  uint64_t rays = 0;           // closest-hit rays of all traced paths
  double ms = 0.0;             // wall time of generation
  bool path_limit_reached = false;  // stopped at kMaxPathsPerVpl * vpls paths
  // The clamp c = vpl_clamp_at(clamp_distance, clamp_per_depth, depth): vpl_clamp_distance of
  // this set and 0 (clamp_relative_to = vpl_bounds), or 0 and clamp_fraction (camera_distance).
  float clamp_distance = 0.0f;
  float clamp_per_depth = 0.0f;
  // Per surface hit (index 0 = first hit = one-bounce VPLs): VPL count and summed intensity.
  std::vector<uint64_t> vpls_per_bounce;
  std::vector<dvec3> intensity_per_bounce;
  // brsm: wall time of each stage (gbuffer, texels, filter, mip, warp), summed over the maps.
  std::vector<std::pair<std::string, double>> stage_ms;
};

// Adds `ms` to stage `stage` of stats.stage_ms (a new entry the first time).
void add_stage_ms(VplStats& stats, const char* stage, double ms);

// The clamp of `vpls` (VplStats::clamp_distance and clamp_per_depth) as `p` defines it.
void set_clamp(const VplParams& p, const VplSet& vpls, const Scene& scene, VplStats& st);

// The statistics for a JSON record (per-bounce intensity as RGB triples).
nlohmann::json to_json(const VplStats& stats);

// `focus`: where directional lights aim most of their paths (EmissionFocus, core/lights/light_sample.h).
VplSet generate_vpls(const Scene& scene, const EmbreeAccel& accel, const LightSampler& lights,
                     const VplParams& params, uint32_t seed, bool diffuse_only, VplStats* stats = nullptr,
                     const EmissionFocus& focus = emission_focus_none());

}  // namespace sst
