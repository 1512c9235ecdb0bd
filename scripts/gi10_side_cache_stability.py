#!/usr/bin/env python3
"""GI-1.0's probe stability on a static view, with and without its side cache (side_cache).

For each scene and seed, sst-render renders a static sequence of gi10 (after its cache warm-up)
with side_cache off and on. A static camera shows the same light every frame, so what the
indirect layer changes from frame to frame is instability: the indirect flicker is the RMS over
pixels, channels and consecutive frame pairs of (indirect_t1 - indirect_t0), read with oiiotool.
The per-frame records give the probes that started without history and the side cache's
counters, summed over the frames, and the stage times. Prints a Markdown table.

    SST_SCENE_PATH=../shared/scenes python3 scripts/gi10_side_cache_stability.py \\
        --sst-render build/sst-render --out /tmp/side-cache-stability staircase breakfast-room
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess


def frame_difference_ms2(a, b):
    """Mean over pixels and RGB of (b - a)^2 for the indirect layers of two EXRs, by oiiotool."""
    ch = "--ch indirect.R,indirect.G,indirect.B"
    out = subprocess.run(f"oiiotool {a} {ch} {b} {ch} --sub --printstats", shell=True, check=True,
                         capture_output=True, text=True).stdout
    avg = [float(v) for v in re.search(r"Stats Avg: ([-\d.e+ ]+)", out).group(1).split()[:3]]
    sd = [float(v) for v in re.search(r"Stats StdDev: ([-\d.e+ ]+)", out).group(1).split()[:3]]
    return sum(m * m + s * s for m, s in zip(avg, sd)) / 3.0


def layer_mean(path):
    out = subprocess.run(f"oiiotool {path} --ch indirect.R,indirect.G,indirect.B --printstats", shell=True,
                         check=True, capture_output=True, text=True).stdout
    avg = [float(v) for v in re.search(r"Stats Avg: ([-\d.e+ ]+)", out).group(1).split()[:3]]
    return sum(avg) / 3.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--sst-render", default="build/sst-render")
    ap.add_argument("--out", required=True, help="folder for the frames and records")
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--warmup", type=int, default=32, help="gi10's cache_warmup_frames")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    a = ap.parse_args()
    rows = []
    for scene in a.scenes:
        for side in ("off", "on"):
            flicker, means, no_history, probes, used, evicted, taken, sample_ms, side_ms = [], [], 0, 0, 0, 0, 0, [], []
            for seed in a.seeds:
                d = os.path.join(a.out, f"{scene}-{side}-{seed}")
                os.makedirs(d, exist_ok=True)
                subprocess.run([a.sst_render, scene, "--method", "gi10", "--height", str(a.height), "--spp", "1",
                                "--diffuse-only", "--frames", str(a.frames), "--seed", str(seed), "--cache-warmup-frames",
                                str(a.warmup), "--side-cache", side, "--no-preview", "-q", "-o",
                                os.path.join(d, "out.exr")], check=True)
                record = json.load(open(os.path.join(d, "out.json")))
                images = [f["images"][0] for f in record["frames"]]
                pairs = [frame_difference_ms2(x, y) for x, y in zip(images, images[1:])]
                flicker.append(math.sqrt(sum(pairs) / len(pairs)))
                means.append(statistics.mean(layer_mean(p) for p in images))
                for f in record["frames"]:
                    c = f["method_counters"]
                    no_history += c["probes_without_history"]
                    probes += c["probes"]
                    used += c["side_used"]
                    evicted += c["side_evicted"]
                    taken += c["side_allocated"]
                    t = f["timings_ms"]
                    sample_ms.append(t["gi10_sample"]["median"])
                    side_ms.append(sum(t[k]["median"] for k in t if k.startswith("gi10_side_")))
            rows.append((scene, side, statistics.mean(flicker), flicker, statistics.mean(means), no_history, probes, used,
                         evicted, taken, statistics.median(sample_ms), statistics.median(side_ms)))
    print("| scene | side cache | indirect flicker (seeds) | indirect mean | probes without history / probes | "
          "fed by the side cache | evicted, slots taken | sample ms | side-cache stages ms |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]:.5f} ({', '.join(f'{x:.5f}' for x in r[3])}) | {r[4]:.5f} | {r[5]} / {r[6]} | "
              f"{r[7]} | {r[8]}, {r[9]} | {r[10]:.2f} | {r[11]:.3f} |")


if __name__ == "__main__":
    main()
