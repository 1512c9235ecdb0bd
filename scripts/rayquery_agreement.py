#!/usr/bin/env python3
"""How each method's image with --accel rayquery agrees with the CPU's on the flat BVH.

For every method and scene, renders the same seed with `--backend cpu --accel flat` and with
`--backend vulkan --accel rayquery` and prints one table row: the relative RMSE of the image and
of its direct layer, the relative difference of the image means, and, for the methods that write
an `indirect_variance` layer (the VPL methods), the block z-test of tests/gpu/vulkan_backend_test.cpp
(per 8x8 block, the difference of the indirect layers' mean luminances over its standard error:
the share of blocks with |z| > 3.29, p = 0.001 each, and the whole image's z).

Needs build/sst-render (or --bin), oiiotool (openimageio-tools), a Vulkan device with ray queries
and the scenes on the scene path. Usage:
  scripts/rayquery_agreement.py [--bin PATH] [--scene-dir DIR] [--width N] [--spp N] [--out DIR]
"""
import argparse
import math
import os
import subprocess
import sys

METHODS = {
    "pt": ["--max-bounces", "2"],
    "exhaustive": ["--vpls", "64"],
    "uniform": ["--vpls", "2048"],
    "slc": ["--vpls", "2048"],
    "sst": ["--vpls", "2048"],
    "rtslc": ["--vpls", "2048"],
    "hybrid": ["--vpls", "2048"],
}
SCENES = ["cornell-box/cornell-box.gltf", "breakfast-room/breakfast-room-point.gltf", "staircase/staircase.gltf"]


def read_exr(path):
    """Channel name -> list of floats, row-major, from oiiotool's text dump."""
    info = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True, check=True).stdout
    names = next(line.split(":", 1)[1] for line in info.splitlines() if "channel list" in line)
    names = [n.strip() for n in names.split(",")]
    dump = subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True, check=True).stdout
    channels = {n: [] for n in names}
    for line in dump.splitlines():
        if "Pixel (" not in line:
            continue
        values = line.split(":", 1)[1].split()
        for n, v in zip(names, values):
            channels[n].append(float(v))
    width = int(info.split(" x ")[0].split(":")[-1].strip().split()[-1])
    return channels, width


def luminance(ch, prefix, i):
    return 0.2126 * ch[prefix + "R"][i] + 0.7152 * ch[prefix + "G"][i] + 0.0722 * ch[prefix + "B"][i]


def relative_rmse(a, b, prefix):
    keys = [prefix + c for c in "RGB"]
    n = len(a[keys[0]]) * 3
    s = sum((a[k][i] - b[k][i]) ** 2 for k in keys for i in range(len(a[k])))
    m = sum(abs(b[k][i]) for k in keys for i in range(len(b[k])))
    return math.sqrt(s / n) / (m / n) if m > 0 else math.sqrt(s / n)


def block_z(a, b, width):
    if "indirect_variance.R" not in a or "indirect_variance.R" not in b:
        return None
    height = len(a["indirect.R"]) // width
    outliers = blocks = 0
    diff_all = var_all = 0.0
    for by in range(0, height, 8):
        for bx in range(0, width, 8):
            diff = var = 0.0
            for y in range(by, min(by + 8, height)):
                for x in range(bx, min(bx + 8, width)):
                    i = y * width + x
                    diff += luminance(a, "indirect.", i) - luminance(b, "indirect.", i)
                    var += luminance(a, "indirect_variance.", i) + luminance(b, "indirect_variance.", i)
            diff_all += diff
            var_all += var
            blocks += 1
            if (abs(diff) / math.sqrt(var) > 3.29) if var > 0 else abs(diff) > 1e-6:
                outliers += 1
    return outliers / blocks, (diff_all / math.sqrt(var_all) if var_all > 0 else 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="build/sst-render")
    ap.add_argument("--scene-dir", default=None)
    ap.add_argument("--width", type=int, default=96)
    ap.add_argument("--spp", type=int, default=8)
    ap.add_argument("--out", default="out/rayquery-agreement")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scene_dirs = ["--scene-dir", args.scene_dir] if args.scene_dir else []
    print("| scene | method | rel. RMSE image | rel. RMSE direct | mean difference | blocks |z| > 3.29 | image z |")
    print("|---|---|---|---|---|---|---|")
    for scene in SCENES:
        for method, params in METHODS.items():
            images = {}
            for backend, accel in (("cpu", "flat"), ("vulkan", "rayquery")):
                out = os.path.join(args.out, f"{os.path.basename(scene).split('.')[0]}-{method}-{accel}.exr")
                subprocess.run([args.bin, scene, *scene_dirs, "--method", method, *params, "--backend", backend,
                                "--accel", accel, "--width", str(args.width), "--spp", str(args.spp), "--seed", "7",
                                "-q", "-o", out], check=True)
                images[accel] = read_exr(out)
            (rq, width), (flat, _) = images["rayquery"], images["flat"]
            mean = lambda ch: sum(ch["R"]) + sum(ch["G"]) + sum(ch["B"])
            z = block_z(rq, flat, width)
            zs = f"{100 * z[0]:.1f}% | {z[1]:+.2f}" if z else "- | -"
            print(f"| {scene.split('/')[0]} | {method} | {relative_rmse(rq, flat, ''):.2e} | "
                  f"{relative_rmse(rq, flat, 'direct.'):.2e} | {mean(rq) / mean(flat) - 1:+.2%} | {zs} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
