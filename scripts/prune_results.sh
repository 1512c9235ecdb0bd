#!/usr/bin/env bash
# Shrinks a results folder for committing: keeps results.json/csv, table.md, report.html, the
# reference PNGs and the seed-0 image and videos of each sweep point (what the report shows); deletes the
# float EXRs, error heat maps and the PNGs of the other seeds, then rewrites the report, which
# leaves out images that are no longer there. Usage: scripts/prune_results.sh results/X ...
set -euo pipefail
cd "$(dirname "$0")/.."
for dir in "$@"; do
  [ -f "$dir/results.json" ] || { echo "error: $dir: no results.json" >&2; exit 1; }
  find "$dir" -name '*.exr' -not -path "$dir/statistics/*" -delete  # statistics/: the check's baseline
  find "$dir/runs" -name error.png -delete
  keep=$(/usr/bin/env python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); print("\n".join(g["runs"][0] for g in r["groups"]))' "$dir/results.json" 2>/dev/null || true)
  if [ -n "$keep" ]; then
    for run in "$dir"/runs/*/; do
      id=$(basename "$run")
      grep -qx "$id" <<<"$keep" || rm -f "$run/image.png" "$run/video.mp4" "$run/reference.mp4"
    done
  fi
  ./build/sst-eval report "$dir"
done
