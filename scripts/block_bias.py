#!/usr/bin/env python3
"""Local bias of one layer between the variants of an sst-eval results folder, per block of pixels.

The image mean hides a bias that is positive in some places and negative in others (light moved from
one surface to another). For each scene and variant, every run's layer (default `indirect`) is
averaged over blocks of `--block` pixels (oiiotool's box filter), and each block and channel is
compared with the control variant's over the seeds by Welch's t. Prints per variant: the largest
|t|, how many of the block-channels exceed `--t` (default 4.5; with ~500 comparisons an unbiased
variant exceeds it with probability below 1%), and the relative difference (variant / control - 1)
of those, as median and largest magnitude.
Usage: scripts/block_bias.py results/restir-gi-glossy --control "no reuse" [--layer indirect] [--block 10] [--t 4.5]
"""
import argparse
import json
import os
import re
import subprocess
import tempfile


def block_means(exr, layer, block):
    info = subprocess.run(["oiiotool", "--info", exr], capture_output=True, text=True, check=True).stdout
    w, h = (int(v) for v in re.search(r"(\d+) x\s+(\d+)", info).groups())
    with tempfile.TemporaryDirectory() as tmp:
        small = os.path.join(tmp, "blocks.exr")
        subprocess.run(["oiiotool", exr, "--ch", ",".join("%s.%s" % (layer, c) for c in "RGB"), "--resize:filter=box",
                        "%dx%d" % (w // block, h // block), "-o", small], check=True)
        dump = subprocess.run(["oiiotool", "--dumpdata", small], capture_output=True, text=True, check=True).stdout
    values = []
    for line in dump.splitlines():
        m = re.match(r"\s*Pixel \(\d+, \d+\): (.*)", line)
        if m:
            values.extend(float(v) for v in m.group(1).split())
    return values


def mean(xs):
    return sum(xs) / len(xs)


def var(xs):
    m = mean(xs)
    return sum((x - m) ** 2 for x in xs) / (len(xs) - 1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("folder")
    ap.add_argument("--control", required=True)
    ap.add_argument("--layer", default="indirect")
    ap.add_argument("--block", type=int, default=10)
    ap.add_argument("--t", type=float, default=4.5)
    a = ap.parse_args()
    runs = {}
    root = os.path.join(a.folder, "runs")
    for run in sorted(os.listdir(root)):
        rec = json.load(open(os.path.join(root, run, "run.json")))
        key = (rec["scene"], rec.get("variant") or rec["label"])
        runs.setdefault(key, []).append(block_means(os.path.join(root, run, "image.exr"), a.layer, a.block))
    print("| scene | variant | seeds | largest abs(t) | blocks over %.1f | their difference: median | largest |" % a.t)
    print("|---|---|---|---|---|---|---|")
    for (scene, variant), images in runs.items():
        control = runs.get((scene, a.control))
        if variant == a.control or not control:
            continue
        largest, diffs = 0.0, []
        cells = len(images[0])
        for i in range(cells):
            x = [im[i] for im in images]
            y = [im[i] for im in control]
            se = (var(x) / len(x) + var(y) / len(y)) ** 0.5
            if se <= 0:
                continue
            t = (mean(x) - mean(y)) / se
            largest = max(largest, abs(t))
            if abs(t) > a.t and mean(y) > 0:
                diffs.append(mean(x) / mean(y) - 1.0)
        diffs.sort(key=abs)
        med = "%+.1f%%" % (100 * diffs[len(diffs) // 2]) if diffs else "-"
        top = "%+.1f%%" % (100 * diffs[-1]) if diffs else "-"
        print("| %s | %s | %d | %.1f | %d of %d | %s | %s |" % (scene, variant, len(images), largest, len(diffs), cells,
                                                               med, top))


if __name__ == "__main__":
    main()
