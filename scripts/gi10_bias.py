#!/usr/bin/env python3
"""Bias of gi10's indirect light per channel in an sst-eval results folder (configs/gi10-static*.json).

The references are single images (direct + indirect). Each run's EXR has the layers `direct` (sst's
direct pass, unbiased) and `indirect` (GI-1.0's estimate), so the reference's indirect mean is
mean(reference) - mean(run.direct), and the bias of the indirect light is
mean(run.indirect) / that - 1 per channel (the direct pass's noise moves the image mean by < 0.3%
at 1 spp over these images). Prints one row per point of the axes and variant, seeds pooled (mean,
and the standard deviation over seeds): image RMSE, SSIM, the image mean's bias (mean(run) /
mean(reference) - 1 over the three channels' sum), the share of probe hits that took the feedback
image, and the indirect bias (R, G, B).
Usage: scripts/gi10_bias.py results/gi10-static [--markdown]
"""
import json
import os
import re
import subprocess
import sys


def layer_means(exr, layer):
    out = subprocess.run(["oiiotool", "-v", "--info", "--stats", exr], capture_output=True, text=True,
                         check=True).stdout
    names = [c.strip() for c in re.search(r"channel list: (.*)", out).group(1).split(",")]
    avg = [float(v) for v in re.search(r"Stats Avg: ([^(]*)", out).group(1).split()]
    return [avg[names.index("%s.%s" % (layer, c))] for c in "RGB"]


def main():
    folder = sys.argv[1]
    markdown = "--markdown" in sys.argv
    groups = {}
    runs = os.path.join(folder, "runs")
    for run in sorted(os.listdir(runs)):
        rec = json.load(open(os.path.join(runs, run, "run.json")))
        exr = os.path.join(runs, run, "image.exr")
        direct = layer_means(exr, "direct")
        indirect = layer_means(exr, "indirect")
        ref = rec["metrics"]["mean_reference"]
        bias = [ind / (r - d) - 1.0 if r - d > 0 else float("nan") for ind, r, d in zip(indirect, ref, direct)]
        key = (rec["scene"],) + tuple(sorted((k, str(v)) for k, v in rec["axes"].items()))
        if rec.get("variant"):
            key += (("variant", rec["variant"]),)
        image = sum(rec["metrics"]["mean_test"]) / sum(ref) - 1.0
        mc = rec["counters"].get("method", {})
        feedback = mc.get("feedback_rays", 0) / mc["probe_hits"] if mc.get("probe_hits") else float("nan")
        groups.setdefault(key, []).append((rec["metrics"]["rmse"], rec["metrics"]["ssim"], bias, image, feedback))
    axes = [k for k, _ in next(iter(groups))[1:]] if groups else []
    if markdown:
        print("| scene | " + " | ".join(axes) + " | seeds | RMSE | SSIM | image bias | feedback share | indirect bias R | G | B |")
        print("|---|" + "---|" * len(axes) + "---|---|---|---|---|---|---|---|")
    for key, rows in groups.items():
        n = len(rows)
        mean = lambda xs: sum(xs) / len(xs)
        sd = lambda xs: (sum((x - mean(xs)) ** 2 for x in xs) / (len(xs) - 1)) ** 0.5 if len(xs) > 1 else 0.0
        rmse = mean([r[0] for r in rows])
        ssim = mean([r[1] for r in rows])
        cells = []
        for c in range(3):
            b = [r[2][c] for r in rows]
            cells.append("%+.1f%% (sd %.1f)" % (100 * mean(b), 100 * sd(b)) if n > 1 else "%+.1f%%" % (100 * b[0]))
        values = [v for _, v in key[1:]]
        image = [r[3] for r in rows]
        image_cell = "%+.1f%% (sd %.1f)" % (100 * mean(image), 100 * sd(image)) if n > 1 else "%+.1f%%" % (100 * image[0])
        feedback = "%.2f" % mean([r[4] for r in rows])
        if markdown:
            print("| %s | %s | %d | %.4f | %.3f | %s | %s | %s |" % (key[0], " | ".join(values), n, rmse, ssim, image_cell,
                                                                     feedback, " | ".join(cells)))
        else:
            print("%-15s %s  n=%d rmse %.4f ssim %.3f  image %s  feedback %s  bias %s" % (
                key[0], " ".join(values), n, rmse, ssim, image_cell, feedback, " | ".join(cells)))


if __name__ == "__main__":
    main()
