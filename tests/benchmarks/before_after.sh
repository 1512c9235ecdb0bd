#!/bin/bash
# CPU speed of two builds, interleaved: the path-tracing benchmarks (sst_benchmarks) and every
# method's stage times in sst-render on breakfast-room-point (256 px wide, 4 spp, 2 threads; the
# VPL methods with 100k VPLs, exhaustive with 1000, pt with 8 bounces, gi10 with its defaults),
# medians over ROUNDS rounds. `frame` is the sum of a method's stages after the scene is loaded
# and its accel built (load, accel_build and write are left out: no method changes them).
#   tests/benchmarks/before_after.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [ROUNDS]
# Run on an otherwise idle machine. Scene: SST_SCENE_DIR (default /work/shared/scenes).
# METHODS (default: all of them) chooses methods. FRAMES=N (default 1) renders N-frame sequences
# instead of single frames: each stage is then the median over the frames, which leaves out the
# first frame's page faults (a renderer's steady state: storage reused across frames).
# BEFORE_ARGS and AFTER_ARGS add sst-render options to one side, to compare two settings of one
# build (e.g. BEFORE_ARGS="--leaves stored" AFTER_ARGS="--leaves made", both dirs the same);
# VPLS (default 100000) and SPP (default 4) change the VPL methods' count and the samples.
# PT_FILTER (default 'BM_PathTrace(Staircase|CornellBox)') chooses the path-tracing benchmarks,
# e.g. BM_PathTraceCornellBox against a build whose staircase benchmark cannot find its scene.
set -euo pipefail
before=${1:?before build dir}; after=${2:?after build dir}; rounds=${3:-3}
scene=${SST_SCENE_DIR:-/work/shared/scenes}/breakfast-room/breakfast-room-point.gltf
[ -f "$scene" ] || { echo "error: $scene not found (set SST_SCENE_DIR)" >&2; exit 1; }
methods=${METHODS:-"pt exhaustive uniform slc sst rtslc hybrid gi10"}
pt_filter=${PT_FILTER:-'BM_PathTrace(Staircase|CornellBox)'}
frames=${FRAMES:-1}
vpls=${VPLS:-100000}
spp=${SPP:-4}
read -r -a before_args <<< "${BEFORE_ARGS:-}"
read -r -a after_args <<< "${AFTER_ARGS:-}"
sequence=()
[ "$frames" -gt 1 ] && sequence=(--frames "$frames" --no-preview)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq "$rounds"); do
  for b in before after; do
    dir=$before; args=("${before_args[@]}")
    [ "$b" = after ] && { dir=$after; args=("${after_args[@]}"); }
    "$dir/tests/sst_benchmarks" --benchmark_filter="$pt_filter" 2>/dev/null | grep '^BM_' |
      awk -v b=$b '{print b, $1, $2}' >> "$out/pt.txt"
    for m in $methods; do
      extra=(--vpls "$vpls")
      case $m in
        pt) extra=(--max-bounces 8) ;;
        gi10) extra=() ;;
        exhaustive) extra=(--vpls 1000) ;;
      esac
      "$dir/sst-render" "$scene" --method $m "${extra[@]}" "${sequence[@]}" "${args[@]}" --spp "$spp" --width 256 --threads 2 -q \
        -o "$out/$b-$m-$r.exr" --json "$out/$b-$m-$r.json" > /dev/null
    done
  done
done
python3 - "$out" "$methods" <<'PY'
import collections, glob, json, statistics, sys
out, methods = sys.argv[1], sys.argv[2].split()
pt = collections.defaultdict(list)
for line in open(out + '/pt.txt'):
    b, name, ms = line.split()
    # The benchmark's name with its arguments (BM_PathTraceStaircase/1024), without Google
    # Benchmark's settings (/min_time:4.000, /manual_time, /iterations:7).
    key = '/'.join(p for p in name.split('/') if ':' not in p and p != 'manual_time')
    pt[(key, b)].append(float(ms))
print(f"{'benchmark':28s} {'before':>9s} {'after':>9s} {'after/before':>12s}")
for name in sorted({n for n, _ in pt}):
    # A benchmark one build lacks (or names with other arguments) shows as "-".
    a, z = (statistics.median(pt[(name, s)]) if pt.get((name, s)) else None for s in ('before', 'after'))
    show = lambda v: f"{v:9.1f}" if v is not None else f"{'-':>9s}"
    ratio = f"{z / a:12.3f}" if a and z is not None else f"{'-':>12s}"
    print(f"{name:28s} {show(a)} {show(z)} {ratio}")
skip = {'load', 'accel_build', 'write'}
st = collections.defaultdict(list)
for f in glob.glob(out + '/*.json'):
    b, m, _ = f.split('/')[-1][:-5].split('-')
    t = json.load(open(f))['timings_ms']
    stages = {k: v['median'] for k, v in t.items() if k not in skip}
    stages['frame'] = sum(stages.values())
    for k, v in stages.items(): st[(m, k, b)].append(v)
print(f"\n{'method':10s} {'stage':16s} {'before ms':>10s} {'after ms':>10s} {'after/before':>12s}   (medians of {len(st[(methods[0], 'frame', 'before')])})")
for m in methods:
    for k in sorted({k for mm, k, _ in st if mm == m}, key=lambda k: (k == 'frame', k)):
        a, z = statistics.median(st[(m, k, 'before')]), statistics.median(st[(m, k, 'after')])
        print(f"{m:10s} {k:16s} {a:10.2f} {z:10.2f} {z / a if a else float('nan'):12.3f}")
PY
