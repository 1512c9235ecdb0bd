#!/usr/bin/env bash
# Side-by-side speed of sst-render's path tracer and Blender Cycles (CPU) on the
# shared reference scenes, rendered the way the references were made
# (/work/shared/tools/render_gltf.py: diffuse-only, 8 bounces, box filter, no
# clamping/denoising), with the same resolution, spp and thread count.
#
# usage: tests/benchmarks/cycles_side_by_side.sh [SPP]        (default SPP 16)
# env:   SST_SCENE_DIR   scene folder             [/work/shared/scenes]
#        SST_RENDER      sst-render binary        [<repo>/build/sst-render]
#        RENDER_GLTF     Blender render script    [/work/shared/tools/render_gltf.py]
#        BLENDER         blender binary           [blender]
#        THREADS         threads for both         [2]
#        SCENES          scenes of MANIFEST.json  [staircase breakfast-room cornell-box]
#        KEEP_TMP=1      keep the temp folder (images, logs, JSON)
#        SST_ARGS        more sst-render options, e.g. "--path-batch 0" []
#
# Columns:
#   cycles_ms/spp   Cycles render_s / spp as printed by render_gltf.py (REFSTATS line):
#                   bpy.ops.render.render only (excludes Blender startup and glTF
#                   import), but includes Cycles' scene sync, BVH build and EXR save.
#   sst_ms/spp      sst-render timings_ms.render.median / spp (median of 3 repeats;
#                   excludes load and acceleration-structure build).
#   ratio           cycles_ms/spp / sst_ms/spp  (>1: sst is faster).
#   sst_Mrays/s     counters.mrays_per_s from sst-render's JSON.
#   cycles_pt_ms/spp  Cycles sampling only: time between its "Sample 0/N" and
#                   "Sample N/N" progress lines (no sync/BVH/save); informational,
#                   closer to what sst_ms/spp measures.
# A fair comparison needs an otherwise idle machine.
set -euo pipefail

SPP="${1:-16}"
if ! [[ "$SPP" =~ ^[1-9][0-9]*$ ]]; then
  echo "error: SPP must be a positive integer (got '$SPP')" >&2; exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
SCENE_DIR="${SST_SCENE_DIR:-/work/shared/scenes}"
SST="${SST_RENDER:-$repo/build/sst-render}"
RENDER_GLTF="${RENDER_GLTF:-/work/shared/tools/render_gltf.py}"
BLENDER="${BLENDER:-blender}"
THREADS="${THREADS:-2}"
BOUNCES=8

die() { echo "error: $*" >&2; exit 1; }
if ! command -v "$BLENDER" >/dev/null 2>&1; then
  echo "skipped: blender not found ('$BLENDER'); install it (apt-get install -y blender, Debian 12: Blender 3.4) or set BLENDER=/path/to/blender"
  exit 0
fi
command -v python3 >/dev/null 2>&1 || die "python3 not found (needed to read MANIFEST.json and the sst JSON)"
[[ -x "$SST" ]] || die "sst-render not found or not executable at '$SST' (build it, or set SST_RENDER)"
[[ -f "$RENDER_GLTF" ]] || die "render_gltf.py not found at '$RENDER_GLTF' (set RENDER_GLTF)"
[[ -f "$SCENE_DIR/MANIFEST.json" ]] || die "no MANIFEST.json in scene dir '$SCENE_DIR' (set SST_SCENE_DIR)"

tmp="$(mktemp -d "${TMPDIR:-/tmp}/cycles_side_by_side.XXXXXX")"
if [[ "${KEEP_TMP:-0}" == 1 ]]; then
  echo "# temp folder kept: $tmp"
else
  trap 'rm -rf "$tmp"' EXIT
fi

blender_version="$("$BLENDER" --version 2>/dev/null | head -n1 || true)"
cpu_model="$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: *//' || true)"
[[ -n "$cpu_model" ]] || cpu_model="$(uname -m)"
echo "# Blender: ${blender_version:-unknown}"
echo "# CPU: ${cpu_model} ($(nproc) hardware threads); threads used: $THREADS"
echo "# sst-render: $SST ${SST_ARGS:-}"
echo "# settings: diffuse-only, max $BOUNCES indirect bounces, spp $SPP, Cycles 1 run, sst median of 3 (--repeat 3)"
echo "# load average at start: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"

# Per scene: camera (lookat/yfov) and resolution of its reference render, from MANIFEST.json.
# Prints: file W H yfov ex ey ez cx cy cz ux uy uz
scene_params() {
  python3 - "$SCENE_DIR/MANIFEST.json" "$1" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1])); s = sys.argv[2]
v = m["scenes"][s]["variants"][s]
r = v["renders"][0]
w, h = r.get("res", v["camera"]["res"])
look = r.get("lookat", v["camera"]["lookat_args"])
yfov = r.get("yfov_rad", v["camera"]["yfov_rad"])
print(v["file"], w, h, repr(yfov), *[repr(x) for x in look])
EOF
}

# "Time:MM:SS.ss" / "Time:HH:MM:SS.ss" of the Cycles progress line matching a pattern -> seconds
cycles_pt_seconds() {
  python3 - "$1" "$2" <<'EOF'
import re, sys
log, n = open(sys.argv[1], errors="replace").read().splitlines(), sys.argv[2]
def secs(line):
    m = re.search(r"\| Time:([0-9:.]+) \|", line)
    if not m: return None
    t = 0.0
    for p in m.group(1).split(":"): t = 60 * t + float(p)
    return t
t0 = [secs(l) for l in log if l.endswith("| Sample 0/%s" % n)]
t1 = [secs(l) for l in log if l.endswith("| Sample %s/%s" % (n, n))]
print("%.6f" % (t1[-1] - t0[-1]) if t0 and t1 and t0[-1] is not None and t1[-1] is not None else "nan")
EOF
}

rows=()
for scene in ${SCENES:-staircase breakfast-room cornell-box}; do
  read -r file W H YFOV ex ey ez cx cy cz ux uy uz < <(scene_params "$scene") || die "scene '$scene' not in MANIFEST.json"
  gltf="$SCENE_DIR/$file"
  [[ -f "$gltf" ]] || die "scene file not found: $gltf"
  echo "# $scene: ${W}x${H}, rendering with Cycles ..." >&2

  clog="$tmp/$scene.cycles.log"
  if ! "$BLENDER" -b --factory-startup -noaudio --python "$RENDER_GLTF" -- \
        --scene "$gltf" --out "$tmp/$scene.cycles" --res "$W" --resy "$H" \
        --spp "$SPP" --bounces "$BOUNCES" --diffuse-only --threads "$THREADS" \
        --lookat "$ex" "$ey" "$ez" "$cx" "$cy" "$cz" "$ux" "$uy" "$uz" --yfov "$YFOV" \
        >"$clog" 2>&1; then
    tail -n 30 "$clog" >&2; die "Blender/Cycles render of $scene failed (log above)"
  fi
  refstats="$(grep '^REFSTATS' "$clog" | tail -n1 || true)"
  [[ -n "$refstats" ]] || { tail -n 30 "$clog" >&2; die "no REFSTATS line in Cycles output for $scene"; }
  grep -q "res=${W}x${H}" <<<"$refstats" || die "Cycles rendered at unexpected size: $refstats"
  cycles_render_s="$(sed -n 's/.*render_s=\([0-9.]*\).*/\1/p' <<<"$refstats")"
  cycles_import_s="$(sed -n 's/.*import_s=\([0-9.]*\).*/\1/p' <<<"$refstats")"
  cycles_pt_s="$(cycles_pt_seconds "$clog" "$SPP")"

  echo "# $scene: rendering with sst-render ..." >&2
  sjson="$tmp/$scene.sst.json"
  if ! "$SST" "$gltf" -o "$tmp/$scene.sst.exr" --json "$sjson" \
        --width "$W" --height "$H" --spp "$SPP" --diffuse-only --max-bounces "$BOUNCES" \
        --threads "$THREADS" -q --repeat 3 ${SST_ARGS:-} >"$tmp/$scene.sst.log" 2>&1; then
    tail -n 30 "$tmp/$scene.sst.log" >&2; die "sst-render of $scene failed (log above)"
  fi
  read -r sst_ms mrays < <(python3 - "$sjson" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
print(d["timings_ms"]["render"]["median"], d["counters"]["mrays_per_s"])
EOF
  ) || die "could not read timings_ms.render.median / counters.mrays_per_s from $sjson"

  rows+=("$(python3 - "$scene" "$SPP" "$cycles_render_s" "$sst_ms" "$mrays" "$cycles_pt_s" "$W" "$H" "$cycles_import_s" <<'EOF'
import sys
scene, spp, cyc_s, sst_ms, mrays, pt_s, w, h, imp = sys.argv[1:]
spp = int(spp)
c = 1000 * float(cyc_s) / spp
s = float(sst_ms) / spp
pt = 1000 * float(pt_s) / spp
print("%-14s %9s %5d %14.2f %11.2f %7.2f %12.2f %17.2f" %
      (scene, "%sx%s" % (w, h), spp, c, s, c / s, float(mrays), pt))
EOF
  )")
done

printf '%-14s %9s %5s %14s %11s %7s %12s %17s\n' scene res spp "cycles_ms/spp" "sst_ms/spp" ratio "sst_Mrays/s" "cycles_pt_ms/spp"
printf '%s\n' "${rows[@]}"
echo "# ratio = cycles_ms/spp / sst_ms/spp (>1: sst faster). cycles_ms/spp includes Cycles' sync/BVH/EXR save;"
echo "# cycles_pt_ms/spp is its sampling time only. Use an otherwise idle machine for meaningful numbers."
echo "# load average at end: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
