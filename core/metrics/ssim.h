// Structural similarity (Wang et al. 2004) exactly as sst's metrics define it, i.e. scikit-image's
// structural_similarity(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
// data_range=1): 11x11 Gaussian window (sigma 1.5, truncate 3.5 -> radius 5, normalised),
// K1 0.01, K2 0.03, population covariance, scipy 'reflect' borders, and the mean taken over the
// map with a 5-pixel border cropped. Inputs are display images (values in [0,1]).
#pragma once
#include "core/image/image.h"

namespace sst {

// The Gaussian window's radius; also the border cropped before averaging the SSIM map.
inline constexpr int kSsimRadius = 5;

// Mean SSIM of one channel. NaN when either side is smaller than the 11x11 window: scikit-image
// refuses such images, and any number would be one it cannot reproduce.
double ssim_channel(const Image& a, const Image& b, int channel);
// Mean over channels of ssim_channel (scikit-image's channel_axis=-1). Throws sst::Error on
// mismatched sizes or channel counts.
double ssim(const Image& a, const Image& b);
// The per-pixel SSIM map of every channel, uncropped (its border depends on the reflect mode);
// defined for any size, since only the cropped mean needs the window to fit.
Image ssim_map(const Image& a, const Image& b);

}  // namespace sst
