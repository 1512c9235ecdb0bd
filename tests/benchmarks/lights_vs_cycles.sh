#!/usr/bin/env bash
# Equal-time error of sst-render's path tracer with each light sampler against Blender Cycles
# (CPU) on a many-light scene, both measured against one Cycles reference at high spp (issue 13's
# side-by-side). Cycles renders SPP samples; its render time (REFSTATS render_s: Cycles' sync,
# BVH and sampling) is the budget; sst-render gets the spp that fits that budget at its measured
# ms per spp (render time only, median of 3), and both images are compared with the reference
# by `sst-eval compare`. Diffuse-only, 8 bounces, box filter, the same resolution and threads.
# Blender 3.4 (Debian 12) samples lights without a light tree (its light tree came in 3.5).
#
# usage: tests/benchmarks/lights_vs_cycles.sh SCENE.gltf REFERENCE.exr [SPP]   (default SPP 32)
# env:   SST_RENDER, SST_EVAL  binaries                 [<repo>/build/sst-render, sst-eval]
#        RENDER_GLTF          Blender render script      [/work/shared/tools/render_gltf.py]
#        BLENDER              blender binary             [blender]
#        THREADS              threads for both           [2]
#        SAMPLERS             sst light samplers         ["power tree slc"]
# The reference must have the resolution of the renders (WxH of the reference EXR are used).
# A fair comparison needs an otherwise idle machine.
set -euo pipefail

die() { echo "error: $*" >&2; exit 1; }
[[ $# -ge 2 ]] || die "usage: $0 SCENE.gltf REFERENCE.exr [SPP]"
SCENE="$1"; REF="$2"; SPP="${3:-32}"
[[ "$SPP" =~ ^[1-9][0-9]*$ ]] || die "SPP must be a positive integer (got '$SPP')"
[[ -f "$SCENE" ]] || die "scene '$SCENE' not found"
[[ -f "$REF" ]] || die "reference '$REF' not found"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
SST="${SST_RENDER:-$repo/build/sst-render}"
EVAL="${SST_EVAL:-$repo/build/sst-eval}"
RENDER_GLTF="${RENDER_GLTF:-/work/shared/tools/render_gltf.py}"
BLENDER="${BLENDER:-blender}"
THREADS="${THREADS:-2}"
SAMPLERS="${SAMPLERS:-power tree slc}"
command -v "$BLENDER" >/dev/null 2>&1 || { echo "skipped: blender not found (apt-get install blender python3-numpy)"; exit 0; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

read -r W H < <(python3 - "$EVAL" "$REF" <<'EOF'
import json, subprocess, sys
out = subprocess.run([sys.argv[1], "compare", "--json", sys.argv[2], sys.argv[2]], capture_output=True, text=True, check=True).stdout
j = json.loads(out)
print(j.get("width", 0), j.get("height", 0))
EOF
)
[[ "$W" -gt 0 && "$H" -gt 0 ]] || die "could not read the size of $REF"

rmse() { "$EVAL" compare --json "$1" "$REF" | python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["rmse"], j.get("rel_rmse", ""))'; }

"$BLENDER" -b --factory-startup -noaudio --python "$RENDER_GLTF" -- --scene "$SCENE" --out "$tmp/cycles" \
  --res "$W" --resy "$H" --spp "$SPP" --bounces 8 --diffuse-only --threads "$THREADS" > "$tmp/cycles.log" 2>&1 \
  || { tail -n 20 "$tmp/cycles.log" >&2; die "Cycles render failed"; }
cycles_s="$(sed -n 's/.*render_s=\([0-9.]*\).*/\1/p' "$tmp/cycles.log")"
echo "# $SCENE ${W}x${H}, Cycles $SPP spp in $cycles_s s; reference $REF"
printf "%-10s %8s %10s %12s %12s\n" renderer spp time_s rmse rmse/cycles
read -r c_rmse _ < <(rmse "$tmp/cycles.exr")
printf "%-10s %8s %10.2f %12.5f %12.3f\n" cycles "$SPP" "$cycles_s" "$c_rmse" 1.0
for s in $SAMPLERS; do
  "$SST" "$SCENE" --method pt --diffuse-only --width "$W" --height "$H" --spp 16 --threads "$THREADS" \
    --light-sampler "$s" --repeat 3 -o "$tmp/probe_$s.exr" --json "$tmp/probe_$s.json" -q > /dev/null
  ms_per_spp="$(python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j["timings_ms"]["render"]["median"]/16)' "$tmp/probe_$s.json")"
  spp="$(python3 -c 'import sys; print(max(1, int(float(sys.argv[1]) * 1000 / float(sys.argv[2]))))' "$cycles_s" "$ms_per_spp")"
  "$SST" "$SCENE" --method pt --diffuse-only --width "$W" --height "$H" --spp "$spp" --threads "$THREADS" \
    --light-sampler "$s" -o "$tmp/sst_$s.exr" --json "$tmp/sst_$s.json" -q > /dev/null
  t="$(python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(j["timings_ms"]["render"]["median"]/1000)' "$tmp/sst_$s.json")"
  read -r r _ < <(rmse "$tmp/sst_$s.exr")
  printf "%-10s %8s %10.2f %12.5f %12.3f\n" "sst-$s" "$spp" "$t" "$r" "$(python3 -c "print($r/$c_rmse)")"
done
