#!/usr/bin/env python3
"""Per-variant summary of a sequence sweep with a camera cut (configs/gi10-pan-*.json): median
frame time and its buckets, RMSE and SSIM before and after the cut, flicker, and the recovery: the
frames after the cut until RMSE is within 10% of its median over the last 4 frames.
Usage: scripts/sequence_cut.py results/gi10-pan-breakfast CUT_FRAME [--markdown]
(CUT_FRAME: the index of the first frame after the cut.)
"""
import json
import os
import statistics
import sys


def main():
    folder, cut = sys.argv[1], int(sys.argv[2])
    markdown = "--markdown" in sys.argv
    runs = os.path.join(folder, "runs")
    rows = []
    for run in sorted(os.listdir(runs)):
        rec = json.load(open(os.path.join(runs, run, "run.json")))
        frames = rec.get("frames", [])
        if not frames:
            continue
        before = [f for f in frames if f["index"] < cut]
        after = [f for f in frames if f["index"] >= cut]
        rmse = lambda fs: statistics.median(f["metrics"]["rmse"] for f in fs) if fs else float("nan")
        ssim = lambda fs: statistics.median(f["metrics"]["ssim"] for f in fs) if fs else float("nan")
        tail = statistics.median(f["metrics"]["rmse"] for f in after[-4:]) if after else float("nan")
        recovery = next((i for i, f in enumerate(after) if f["metrics"]["rmse"] <= 1.1 * tail), None)
        ms = statistics.median(f["frame_ms"] for f in frames)
        flicker = rec.get("metrics", {}).get("flicker", rec.get("flicker", float("nan")))
        rows.append((rec["label"], rec.get("options", rec.get("params", {})).get("spp", ""), ms, rmse(before), ssim(before),
                     rmse(after), ssim(after), after[0]["metrics"]["rmse"] if after else float("nan"), recovery,
                     flicker))
    head = ["method", "spp", "frame ms", "RMSE pan", "SSIM pan", "RMSE after cut", "SSIM after cut",
            "RMSE 1st frame after cut", "frames to recover", "flicker"]
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    for r in rows:
        cells = [str(r[0]), str(r[1]), "%.1f" % r[2], "%.4f" % r[3], "%.3f" % r[4], "%.4f" % r[5], "%.3f" % r[6],
                 "%.4f" % r[7], str(r[8]), "%.4f" % r[9] if isinstance(r[9], float) else str(r[9])]
        print(("| " + " | ".join(cells) + " |") if markdown else "  ".join(cells))


if __name__ == "__main__":
    main()
