#!/bin/bash
# How much one VPL set moves the sunlit room's indirect light (results/README.md, "Large
# extents"): `exhaustive` (every VPL, with its shadow ray, so the pixels add no noise of their
# own) over 16 seeds, 100k VPLs, 40x22, on the rooms of scenes/tools/make_window_room.py with
# grounds of 50, 500 and 5000 m half-size, for four settings of where the light paths go
# (directional_focus 4 or 2, focus_bounces 0 or 0.5). Prints, per room and setting, the mean of
# the indirect layer's red channel over the seeds and its standard deviation between seeds.
#
#   scripts/large_extent_vpl_noise.sh OUT_DIR [build]
set -euo pipefail
out=${1:?usage: scripts/large_extent_vpl_noise.sh OUT_DIR [build]}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$root/build}
mkdir -p "$out"
cd "$out"
for h in 50 500 5000; do
  python3 "$root/scenes/tools/make_window_room.py" "window-room-$h.gltf" --half "$h"
  for setting in "4 0" "4 0.5" "2 0" "2 0.5"; do
    set -- $setting
    means=()
    for seed in $(seq 1 16); do
      "$build/sst-render" "window-room-$h.gltf" --method exhaustive --spp 1 --vpls 100000 --width 40 --height 22 \
        --diffuse-only --seed "$seed" --directional-focus "$1" --focus-bounces "$2" -o noise.exr > /dev/null
      means+=("$(oiiotool noise.exr --ch indirect.R --printstats 2>/dev/null | awk '/Stats Avg/ {print $3; exit}')")
    done
    python3 -c 'import statistics as s, sys
v = [float(x) for x in sys.argv[4:]]
m, d = s.mean(v), s.stdev(v)
print("%s m, directional_focus %s, focus_bounces %s: mean %.5f, sd between seeds %.5f (%.1f%%)" % (sys.argv[1], sys.argv[2], sys.argv[3], m, d, 100 * d / m))' \
      "$h" "$1" "$2" "${means[@]}"
  done
done
