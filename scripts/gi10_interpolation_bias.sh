#!/bin/bash
# What is left of GI-1.0's bias with every switchable mechanism in its exact form (expected
# texels, no hysteresis, no cache lookup, texel irradiance, no probe filter, no denoiser, no
# feedback, a path per cache point): the probes' placement and interpolation, which have no exact
# form. Renders the path tracer and that gi10 at several image heights, and prints the bias of the
# indirect light over all pixels and split by the `gi10_probe_hint` layer: pixels given E by a
# probe on their own surface (hint 1) and pixels that fell back on probes off it (hint 0).
#
#   SST_SCENE_PATH=../shared/scenes scripts/gi10_interpolation_bias.sh OUT_DIR SCENE [build]
#   HEIGHTS="90 180 360" SEEDS="1 2 3" PT_SPP=256 (defaults)
#
# One line per render: height seed relaxed-fraction bias(all) bias(hint 1) bias(hint 0)
# share-of-excess(hint 0); bias = sum(gi10 indirect) / sum(path tracer indirect) - 1 over the pixels.
set -euo pipefail
out=${1:?usage: scripts/gi10_interpolation_bias.sh OUT_DIR SCENE [build]}
scene=${2:?usage: scripts/gi10_interpolation_bias.sh OUT_DIR SCENE [build]}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${3:-$root/build}
mkdir -p "$out"
cd "$out"
# The mean of channel R of `image` (a one-layer view) after `ops`.
avg() { oiiotool "$@" --printstats 2>/dev/null | awk '/Stats Avg/ {print $3; exit}'; }
exact=(--texel-estimate expected --no-hysteresis --no-cache-lookup --irradiance-basis texels --no-probe-filter
       --no-irradiance-denoiser --no-feedback --cache-shading path)
for h in ${HEIGHTS:-90 180 360}; do
  [ -f "pt-$h.exr" ] || "$build/sst-render" "$scene" --method pt --spp "${PT_SPP:-256}" --height "$h" --diffuse-only \
    --max-bounces 8 --seed 1000003 -o "pt-$h.exr" -q
  for seed in ${SEEDS:-1 2 3}; do
    g="gi10-$h-$seed.exr"
    "$build/sst-render" "$scene" --method gi10 --spp 1 --height "$h" --diffuse-only --cache-warmup-frames 32 \
      "${exact[@]}" --seed "$seed" -o "$g" -q
    # Luminance-free sums: R + G + B of the indirect layers, times the hint and its complement.
    oiiotool "$g" --ch indirect.R,indirect.G,indirect.B --chsum -o gi.exr
    oiiotool "pt-$h.exr" --ch indirect.R,indirect.G,indirect.B --chsum -o ref.exr
    oiiotool "$g" --ch gi10_probe_hint.R -o hint.exr
    oiiotool hint.exr --mulc -1 --addc 1 -o relaxed.exr
    python3 - "$h" "$seed" "$(avg gi.exr)" "$(avg ref.exr)" "$(avg gi.exr hint.exr --mul)" "$(avg ref.exr hint.exr --mul)" \
      "$(avg gi.exr relaxed.exr --mul)" "$(avg ref.exr relaxed.exr --mul)" "$(avg relaxed.exr)" <<'EOF'
import sys
h, seed = sys.argv[1], sys.argv[2]
g, r, g1, r1, g0, r0, f0 = map(float, sys.argv[3:])
print(f"{h} {seed} relaxed {f0:.4f} bias {g / r - 1:+.4f} hint1 {g1 / r1 - 1:+.4f} hint0 {g0 / r0 - 1:+.4f} "
      f"excess-from-hint0 {(g0 - r0) / (g - r):.2f}")
EOF
  done
done
