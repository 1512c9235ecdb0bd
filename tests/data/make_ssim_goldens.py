#!/usr/bin/python3
"""SSIM golden values for tests/core/metrics/metrics_test.cpp, computed with scikit-image.

Not needed by the build or CI: run it by hand after changing the test images, and paste the
printed values into metrics_test.cpp. Needs Debian's python3-skimage, python3-numpy,
python3-scipy, python3-imageio and, for the EXR pair, python3-openimageio (use /usr/bin/python3,
not a pyenv interpreter, so the Debian modules are found).

The synthetic images are defined by formula; metrics_test.cpp rebuilds them bit for bit (each
value is computed in double and rounded to float32, as the C++ Image stores it).
"""
import math
import os
import sys

import numpy as np
from skimage.metrics import structural_similarity


def ssim(a, b):
    """sst's SSIM: exactly the call the C++ implementation (core/metrics/ssim.h) must reproduce."""
    return structural_similarity(a.astype(np.float64), b.astype(np.float64), gaussian_weights=True,
                                 sigma=1.5, use_sample_covariance=False, data_range=1, channel_axis=-1)


def hash01(x, y, c, seed):
    """lowbias32 of a mixed pixel key, as a float in [0,1); identical to test's hash01."""
    h = (x * 73856093) ^ (y * 19349663) ^ (c * 83492791) ^ (seed * 2654435761)
    h &= 0xFFFFFFFF
    h ^= h >> 16
    h = (h * 0x7FEB352D) & 0xFFFFFFFF
    h ^= h >> 15
    h = (h * 0x846CA68B) & 0xFFFFFFFF
    h ^= h >> 16
    return h / 4294967296.0


def make(width, height, value):
    """float32 image (height, width, 3) with value(x, y, c) computed in double."""
    img = np.empty((height, width, 3), dtype=np.float32)
    for y in range(height):
        for x in range(width):
            for c in range(3):
                img[y, x, c] = value(x, y, c)
    return img


def pattern(x, y, c):
    return 0.5 + 0.45 * math.sin(0.37 * x + 0.23 * y + 1.1 * c) * math.cos(0.19 * y - 0.11 * x + 0.5 * c)


def noisy(x, y, c):
    return min(max(pattern(x, y, c) + 0.3 * (hash01(x, y, c, 7) - 0.5), 0.0), 1.0)


def contrast(x, y, c):
    return 0.7 * pattern(x, y, c) + 0.1 + 0.05 * math.sin(0.5 * x)


def linear_a(x, y, c):
    # Values from -0.2 to 1.4: to_display must clamp before encoding.
    return 1.6 * pattern(x, y, c) ** 2 - 0.2


def linear_b(x, y, c):
    return linear_a(x, y, c) + 0.4 * (hash01(x, y, c, 11) - 0.5)


def srgb_encode(v):
    v = np.clip(v.astype(np.float64), 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)


def synthetic():
    w, h = 40, 32
    print("pattern_vs_noisy_40x32     %.10f" % ssim(make(w, h, pattern), make(w, h, noisy)))
    print("pattern_vs_contrast_40x32  %.10f" % ssim(make(w, h, pattern), make(w, h, contrast)))
    print("noisy_vs_pattern_11x14     %.10f" % ssim(make(11, 14, noisy), make(11, 14, pattern)))
    # Border pixels of the uncropped map depend on scipy's 'reflect' mode.
    _, full = structural_similarity(make(w, h, pattern).astype(np.float64), make(w, h, noisy).astype(np.float64),
                                    gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                    data_range=1, channel_axis=-1, full=True)
    print("map_pattern_noisy(0,0,0)   %.10f" % full[0, 0, 0])
    print("map_pattern_noisy(39,31,2) %.10f" % full[31, 39, 2])
    print("map_pattern_noisy(2,20,1)  %.10f" % full[20, 2, 1])
    la, lb = make(w, h, linear_a), make(w, h, linear_b)
    print("linear_a_vs_b_display      %.10f" % ssim(srgb_encode(la), srgb_encode(lb)))


def read_png(path):
    import imageio
    return imageio.imread(path)[:, :, :3].astype(np.float64) / 255.0


def read_exr_display(path):
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    rgb = buf.get_pixels(oiio.FLOAT)[:, :, :3]
    return srgb_encode(rgb.astype(np.float32))


def real_data():
    ref = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "scenes", "cornell-box", "ref")
    if not os.path.isdir(ref):
        print("(no shared scenes at %s)" % ref, file=sys.stderr)
        return
    a, b = "cornell-box_256spp_seed2", "cornell-box_4096spp_seed1"
    print("cornell_png                %.10f" % ssim(read_png(os.path.join(ref, a + ".png")),
                                                   read_png(os.path.join(ref, b + ".png"))))
    print("cornell_exr_display        %.10f" % ssim(read_exr_display(os.path.join(ref, a + ".exr")),
                                                   read_exr_display(os.path.join(ref, b + ".exr"))))


if __name__ == "__main__":
    synthetic()
    real_data()
