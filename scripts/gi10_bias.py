#!/usr/bin/env python3
"""Bias of gi10's indirect light per channel in an sst-eval results folder (configs/gi10-static*.json).

The references are single images (direct + indirect). Each run's EXR has the layers `direct` (sst's
direct pass, unbiased) and `indirect` (GI-1.0's estimate), so the reference's indirect mean is
mean(reference) - mean(run.direct), and the bias of the indirect light is
mean(run.indirect) / that - 1 per channel (the direct pass's noise moves the image mean by < 0.3%
at 1 spp over these images). Prints one row per run: scene, cache warm-up frames, image RMSE, SSIM,
the indirect bias (R, G, B), and the time of the measured frame.
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
    rows = []
    runs = os.path.join(folder, "runs")
    for run in sorted(os.listdir(runs)):
        rec = json.load(open(os.path.join(runs, run, "run.json")))
        exr = os.path.join(runs, run, "image.exr")
        direct = layer_means(exr, "direct")
        indirect = layer_means(exr, "indirect")
        ref = rec["metrics"]["mean_reference"]
        bias = [ind / (r - d) - 1.0 if r - d > 0 else float("nan") for ind, r, d in zip(indirect, ref, direct)]
        rows.append((rec["scene"], rec["axes"].get("cache_warmup_frames", ""), rec["metrics"]["rmse"],
                     rec["metrics"]["ssim"], bias, rec.get("frame_ms", {}).get("median", float("nan"))
                     if isinstance(rec.get("frame_ms"), dict) else rec.get("frame_ms", float("nan"))))
    if markdown:
        print("| scene | warm-up frames | RMSE | SSIM | indirect bias R | G | B |")
        print("|---|---|---|---|---|---|---|")
    for scene, warm, rmse, ssim, bias, ms in rows:
        b = " | ".join("%+.1f%%" % (100 * v) for v in bias)
        if markdown:
            print("| %s | %s | %.4f | %.3f | %s |" % (scene, warm, rmse, ssim, b))
        else:
            print("%-16s %5s  rmse %.4f  ssim %.3f  bias %s" % (scene, warm, rmse, ssim, b))


if __name__ == "__main__":
    main()
