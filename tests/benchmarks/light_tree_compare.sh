#!/usr/bin/env bash
# Light samplers side by side on scenes with many lights, direct light only (pt, max_bounces 0,
# diffuse-only), as docs/performance.md reports them: for each scene NAME (found as
# SCENES/NAME/NAME.gltf, e.g. written by scenes/tools/make_many_lights.py), a reference at
# REF_SPP, its emitters-only mask (sst-render --emitters-only), then SEEDS renders at SPP
# for each sampler configuration, compared with the reference by `sst-eval compare --mask`: MSE
# and relMSE on all pixels and on the pixels no directly seen emitter touches ("masked"), means
# over the seeds, and the median frame time. Prints one table per scene.
#   tests/benchmarks/light_tree_compare.sh BUILD SCENES [NAME...]
# Environment: HEIGHT (72), SPP (16), SEEDS (16), REF_SPP (4096), OUT (/tmp/light-tree-compare),
# CONFIGS (space-separated name=flags, with commas for spaces; default below).
set -euo pipefail
build=${1:?build folder}
scenes=${2:?scene folder}
shift 2
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(light-field light-field-open night-street)
HEIGHT=${HEIGHT:-72} SPP=${SPP:-16} SEEDS=${SEEDS:-16} REF_SPP=${REF_SPP:-4096} OUT=${OUT:-/tmp/light-tree-compare}
CONFIGS=${CONFIGS:-"power=--light-sampler,power \
morton-box=--light-sampler,tree,--light-tree,morton,--light-tree-distance,box \
saoh-box=--light-sampler,tree,--light-tree,saoh,--light-tree-distance,box \
morton-centre=--light-sampler,tree,--light-tree,morton,--light-tree-distance,centre \
saoh-centre=--light-sampler,tree,--light-tree,saoh,--light-tree-distance,centre \
saoh-mixed=--light-sampler,tree,--light-tree,saoh,--light-tree-distance,mixed"}
render=("$build/sst-render" --max-bounces 0 --diffuse-only --height "$HEIGHT")
mkdir -p "$OUT"
for name in "${names[@]}"; do
  scene="$scenes/$name/$name.gltf"
  ref="$OUT/$name-ref.exr" mask="$OUT/$name-mask.exr"
  [ -f "$ref" ] || "${render[@]}" "$scene" --spp "$REF_SPP" --light-sampler tree --seed 99 -o "$ref" > /dev/null 2>&1
  [ -f "$mask" ] || "${render[@]}" "$scene" --emitters-only --spp 64 -o "$mask" > /dev/null 2>&1
  echo "== $name: ${HEIGHT}p, $SPP spp, $SEEDS seeds, against $REF_SPP spp"
  printf "%-14s %12s %12s %12s %12s %10s\n" config mse rel_mse "mse masked" "rel masked" "frame ms"
  for config in $CONFIGS; do
    label=${config%%=*}
    IFS=, read -r -a flags <<< "${config#*=}"
    sums="0 0 0 0" times=()
    for ((seed = 0; seed < SEEDS; ++seed)); do
      img="$OUT/$name-$label-$seed.exr"
      line=$("${render[@]}" "$scene" --spp "$SPP" --seed "$seed" "${flags[@]}" -o "$img" 2>&1)
      times+=("$(sed -n 's/.*frame \([0-9.]*\) ms.*/\1/p' <<< "$line")")
      json=$("$build/sst-eval" compare "$img" "$ref" --mask "$mask" --json)
      sums=$(python3 -c "import json,sys; j=json.loads(sys.argv[1]); s=[float(x) for x in sys.argv[2].split()]; \
v=[j['rmse']**2, j['rel_mse'], j['masked']['rmse']**2, j['masked']['rel_mse']]; print(' '.join(str(a+b) for a,b in zip(s,v)))" "$json" "$sums")
    done
    python3 -c "import sys, statistics; s=[float(x)/int(sys.argv[2]) for x in sys.argv[1].split()]; \
t=statistics.median(float(x) for x in sys.argv[4:]); print('%-14s %12.4g %12.4g %12.4g %12.4g %10.1f' % (sys.argv[3], *s, t))" \
      "$sums" "$SEEDS" "$label" "${times[@]}"
  done
done
