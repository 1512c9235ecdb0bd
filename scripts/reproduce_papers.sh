#!/usr/bin/env bash
# Renders every paper config into results/<name>/ and writes its tables (Markdown) beside it.
# Usage: scripts/reproduce_papers.sh [config names...]   (default: all paper configs)
# Needs ../shared/scenes (or the folder in SST_SCENE_DIR) and a Release build in build/. References are
# cached (SST_CACHE_DIR, default ~/.cache/sst/references), so a rerun renders only the runs.
set -euo pipefail
cd "$(dirname "$0")/.."
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(sst-table1 sst-table1-denoised sst-table3 thesis-table7-1 thesis-fig7-3 thesis-fig7-5 thesis-fig7-5-denoised thesis-table7-2 sequence-pan sequence-pan-equal-time rtslc-interleave-frames rtslc-tree-build rtslc-weights equal-time gi10-static-one-bounce gi10-static gi10-pan-breakfast gi10-pan-staircase brsm-one-bounce brsm-vpl-count brsm-weights brsm-resolution)
scene_dir="${SST_SCENE_DIR:-../shared/scenes}"
for name in "${configs[@]}"; do
  out="results/$name"
  resume=()
  [ -f "$out/config.json" ] && resume=(--resume)
  ./build/sst-eval sweep "configs/$name.json" -o "$out" --scene-dir "$scene_dir" "${resume[@]}"
  ./build/sst-eval table "$out" --stage vpl_generation --stage tree_build --stage cuts --stage sampling > "$out/table.md"
done
