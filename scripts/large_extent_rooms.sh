#!/bin/bash
# Every method at its defaults on a sunlit room inside grounds of 10 m, 100 m, 1 km and 10 km
# (scenes/tools/make_window_room.py), against Blender Cycles: image means and RMSE, three seeds
# each (results/README.md, "Large extents"; docs/design/lengths.md).
#
#   [SEEDS="4 5 6 7 8"] [HALVES="7 10 14"] [METHODS="slc sst"] [ARGS="--node-distance-floor-above 0"] \
#     [TAG=floor-on] scripts/large_extent_rooms.sh OUT_DIR [build]
#
# HALVES: the grounds' half sizes in metres (default 5 50 500 5000; the room's VPLs then span about
# 0.29 view lengths per metre of half size); METHODS: which methods (default all six); ARGS: further
# sst-render arguments for every render; TAG: a suffix of the renders' file names, so that runs
# with other ARGS share the folder and its references.
#
# Writes the scenes and, where OUT_DIR lacks them, Cycles references (4096 spp, 8 bounces,
# diffuse-only, 320x180: 2-5 minutes each on 2 cores; needs `blender`, `python3-numpy` and
# ../shared/tools/render_gltf.py) into OUT_DIR, then prints one line per render:
#   half-size method seed mean reference-mean rmse
set -euo pipefail
out=${1:?usage: scripts/large_extent_rooms.sh OUT_DIR [build]}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$root/build}
mkdir -p "$out"
cd "$out"
mean() { oiiotool "$1" --ch R,G,B --printstats 2>/dev/null | awk '/Stats Avg/ {print ($3 + $4 + $5) / 3; exit}'; }
for h in ${HALVES:-5 50 500 5000}; do
  python3 "$root/scenes/tools/make_window_room.py" "window-room-$h.gltf" --half "$h"
  if [ ! -f "cycles-$h.exr" ]; then
    blender -b --factory-startup -noaudio --python "$root/../shared/tools/render_gltf.py" -- \
      --scene "window-room-$h.gltf" --out "cycles-$h" --res 320 --resy 180 --spp 4096 --bounces 8 \
      --diffuse-only --threads 2 > "cycles-$h.log" 2>&1
  fi
done
for h in ${HALVES:-5 50 500 5000}; do
  for m in ${METHODS:-pt slc sst rtslc hybrid gi10}; do
    case $m in
      pt) args=(--spp 64) ;;
      gi10) args=(--spp 1) ;;
      *) args=(--spp 8 --vpls 100000) ;;
    esac
    for seed in ${SEEDS:-1 2 3}; do
      f="$m-$h-$seed${TAG:+-$TAG}.exr"
      "$build/sst-render" "window-room-$h.gltf" --method "$m" "${args[@]}" --width 320 --height 180 --diffuse-only \
        --seed "$seed" ${ARGS:-} -o "$f" --json "${f%.exr}.json" > /dev/null
      rmse=$("$build/sst-eval" compare "$f" "cycles-$h.exr" --json | python3 -c 'import json, sys; print("%.4f" % json.load(sys.stdin)["rmse"])')
      echo "$h $m $seed $(mean "$f") $(mean "cycles-$h.exr") $rmse"
    done
  done
done
