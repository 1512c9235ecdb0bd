// FLIP, the perceptual difference evaluator of "FLIP: A Difference Evaluator for Alternating
// Images" (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild; HPG 2020), and its
// HDR form from "Visualizing Errors in Rendered High Dynamic Range Images" (Andersson, Nilsson,
// Shirley, Akenine-Möller; Eurographics 2021 short paper). docs/flip.md describes both.
//
// LDR-FLIP: linear RGB in [0,1] -> YCxCz, filtered by the contrast sensitivity functions of the
// achromatic and the two chromatic channels at the given pixels per degree, -> linearized CIELab
// with the Hunt adjustment, HyAB difference, remapped to [0,1] (qc 0.7, pc 0.4, pt 0.95); edge and
// point features of the luminance (first and second derivatives of a Gaussian, qf 0.5); per pixel
// deltaE_c ^ (1 - deltaE_f). HDR-FLIP: LDR-FLIP of the ACES-tone-mapped images at a range of
// exposures, the per-pixel maximum. The reported number is the mean of the per-pixel map.
#pragma once
#include <limits>
#include <nlohmann/json_fwd.hpp>

#include "core/image/image.h"

namespace sst {

// Pixels per degree of visual angle of a monitor `monitor_width_m` wide showing `resolution_x`
// pixels across, seen from `distance_m` (the small-angle form the paper uses).
constexpr double flip_ppd(double distance_m, double monitor_width_m, double resolution_x) {
  return distance_m * (resolution_x / monitor_width_m) * (3.14159265358979323846 / 180.0);
}

// The papers' default observer: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, about 67 ppd.
inline constexpr double kFlipDefaultPpd = flip_ppd(0.7, 0.7, 3840.0);

struct FlipOptions {
  double ppd = kFlipDefaultPpd;
  // HDR-FLIP only. The exposures (stops, applied as 2^e before tone mapping) run evenly from
  // start to stop; NaN means computed from the reference as the HDR paper does (docs/flip.md), and
  // exposures 0 means max(2, ceil(stop - start)). One exposure needs start == stop.
  double start_exposure = std::numeric_limits<double>::quiet_NaN();
  double stop_exposure = std::numeric_limits<double>::quiet_NaN();
  int exposures = 0;
  bool keep_map = false;  // fill FlipResult::map
};

struct FlipResult {
  double mean = 0.0;  // mean of the map over all pixels, in [0,1]; 0 for an empty image
  Image map;          // 1 channel, the per-pixel FLIP in [0,1]; empty unless keep_map
  // HDR-FLIP: the exposure range and count used (for LDR-FLIP: 0, 0, 0).
  double start_exposure = 0.0, stop_exposure = 0.0;
  int exposures = 0;
};

// Both images are linear RGB, as sst holds them (a PNG read with read_image is already decoded).
// LDR-FLIP sees them as a display shows them at exposure 0: clamped to [0,1] (and sRGB-encoded,
// which FLIP's first step decodes again). Non-finite values count as 0, as in compare_images.
// Throws sst::Error when the shapes differ or the images have other than 3 channels.
FlipResult flip_ldr(const Image& test, const Image& reference, const FlipOptions& options = {});
// HDR-FLIP of linear HDR images; negative and non-finite values count as 0. The exposure range
// comes from the reference only, so HDR-FLIP is not symmetric in its two images.
FlipResult flip_hdr(const Image& test, const Image& reference, const FlipOptions& options = {});

// The ACES filmic curve HDR-FLIP tone-maps with (Narkowicz's fit, applied to 0.6 x), per channel.
float flip_aces(float x);

// {"flip_ldr": mean, "flip_hdr": mean}, null where a mean is not finite. For the metrics of a run.
nlohmann::json flip_json(double ldr, double hdr);
// Both means of linear images, the fields flip_json writes; NaN for images without 3 channels.
nlohmann::json flip_metrics(const Image& test, const Image& reference, const FlipOptions& options = {});

}  // namespace sst
