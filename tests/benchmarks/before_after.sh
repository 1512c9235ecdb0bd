#!/bin/bash
# CPU speed of two builds, interleaved: the path-tracing benchmarks (sst_benchmarks) and the
# many-light stage times of sst-render (vpl_generation, tree_build, sampling) on
# breakfast-room-point with 100k VPLs, medians over ROUNDS rounds.
#   tests/benchmarks/before_after.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [ROUNDS]
# Run on an otherwise idle machine. Scene: SST_SCENE_DIR (default /work/shared/scenes).
set -euo pipefail
before=${1:?before build dir}; after=${2:?after build dir}; rounds=${3:-3}
scene=${SST_SCENE_DIR:-/work/shared/scenes}/breakfast-room/breakfast-room-point.gltf
out=$(mktemp -d)
for r in $(seq "$rounds"); do
  for b in before after; do
    dir=$before; [ "$b" = after ] && dir=$after
    "$dir/tests/sst_benchmarks" --benchmark_filter='BM_PathTrace' 2>/dev/null | grep '^BM_' |
      awk -v b=$b '{print b, $1, $2}' >> "$out/pt.txt"
    for m in slc sst rtslc hybrid; do
      "$dir/sst-render" "$scene" --method $m --vpls 100000 --spp 4 --width 256 --threads 2 -q \
        -o "$out/$b-$m-$r.exr" --json "$out/$b-$m-$r.json" > /dev/null
    done
  done
done
python3 - "$out" <<'PY'
import collections, glob, json, statistics, sys
out = sys.argv[1]
pt = collections.defaultdict(list)
for line in open(out + '/pt.txt'):
    b, name, ms = line.split()
    pt[(name.split('/')[0], b)].append(float(ms))
for (name, b), v in sorted(pt.items()):
    print(f"{name:28s} {b:6s} median {statistics.median(v):8.1f} ms  {v}")
st = collections.defaultdict(list)
for f in glob.glob(out + '/*.json'):
    b, m, _ = f.split('/')[-1][:-5].split('-')
    t = json.load(open(f))['timings_ms']
    for k in ('vpl_generation', 'tree_build', 'sampling'):
        if k in t: st[(m, k, b)].append(t[k]['median'])
for (m, k, b), v in sorted(st.items()):
    print(f"{m:7s} {k:15s} {b:6s} median {statistics.median(v):9.2f} ms  n={len(v)}")
PY
rm -rf "$out"
