#!/usr/bin/env bash
# Frame times of every method on the Vulkan backend, per stage, against the papers' GPU figures.
# One self-contained run: for each scene and image size, each method renders one frame at 1 spp
# (the VPL methods with 100k VPLs, as the SST paper's Tables 2-3) --repeat times, and the table
# gives the medians of the host wall time of each stage and of the device timestamps
# (method_counters.gpu_ms, of the last repetition); the frame time is the timestamps' sum where the
# method has them. GI-1.0's stages, timed by the timestamps, are shown in the paper's three
# buckets (ray tracing, caching and sampling, interpolation and denoising) beside the G-buffer,
# the direct light and the composition. The host times of the first repetition include the driver's shader compilation
# (lavapipe compiles when a pipeline is first dispatched), so --repeat should be 3 or more.
#
# Needs: build/sst-render (or --bin), the Vulkan loader and a driver, python3, and the scenes
# on the scene search path (--scene-dir or SST_SCENE_PATH). Usage:
#   scripts/gpu_bench.sh [--bin PATH] [--scene-dir DIR] [--size WxH]... [--scene NAME]...
#                        [--method NAME]... [--vpls N] [--repeat N] [--accel flat|rayquery] [--out DIR]
# Defaults: sizes 1280x720 and 1920x1080, scenes breakfast-room and staircase, every method,
# 100000 VPLs, 3 repetitions, sst-render's --accel default (ray queries on a GPU that has them),
# out/gpu-bench. Prints the table and writes it to <out>/table.md. Another Vulkan driver is chosen
# through VK_ICD_FILENAMES (docs/vulkan.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/sst-render
sizes=() scenes=() methods=() scene_dirs=()
vpls=100000 repeat=3 out=out/gpu-bench accel=()
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) bin=$2; shift 2 ;;
    --scene-dir) scene_dirs+=(--scene-dir "$2"); shift 2 ;;
    --size) sizes+=("$2"); shift 2 ;;
    --scene) scenes+=("$2"); shift 2 ;;
    --method) methods+=("$2"); shift 2 ;;
    --vpls) vpls=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --accel) accel=(--accel "$2"); shift 2 ;;
    *) echo "gpu_bench: unknown argument '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done
[ ${#sizes[@]} -gt 0 ] || sizes=(1280x720 1920x1080)
[ ${#scenes[@]} -gt 0 ] || scenes=(breakfast-room staircase)
[ ${#methods[@]} -gt 0 ] || methods=(pt sst slc rtslc hybrid gi10)
[ -x "$bin" ] || { echo "gpu_bench: $bin not found (build it, or give --bin)" >&2; exit 2; }
mkdir -p "$out"
"$bin" --list-devices | head -3
for scene in "${scenes[@]}"; do
  for size in "${sizes[@]}"; do
    for method in "${methods[@]}"; do
      extra=()
      case "$method" in pt|gi10) ;; *) extra=(--vpls "$vpls") ;; esac
      name="$out/$scene-$size-$method"
      echo "gpu_bench: $scene $size $method" >&2
      if ! "$bin" "$scene" "${scene_dirs[@]}" --backend vulkan "${accel[@]}" --method "$method" "${extra[@]}" --spp 1 \
        --width "${size%x*}" --height "${size#*x}" --repeat "$repeat" --no-preview -q -o "$name.exr"; then
        echo "gpu_bench: $scene $size $method failed" >&2
      fi
    done
  done
done
python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
setup = {"load", "accel_build", "gpu_setup", "gpu_upload", "light_setup", "shader_compile", "write"}
rows, structures = [], {}
for path in sorted(glob.glob(os.path.join(out, "*.json"))):
    d = json.load(open(path))
    setup_record = d["device"].get("setup", {})
    if "acceleration_structure" in setup_record:
        structures[d["scene"]["source"]] = (d["scene"]["triangles"], setup_record["bvh"], setup_record["acceleration_structure"])
    t = {k: v["median"] for k, v in d["timings_ms"].items()}
    frame = sum(v for k, v in t.items() if k not in setup)
    stages = ", ".join(f"{k} {v:.1f}" for k, v in t.items() if k not in setup)
    mc = d.get("method_counters", {})
    if "buckets_ms" in mc:  # GI-1.0: its stages in the paper's buckets (core/gi10/gi10_method.cpp)
        stages = ", ".join(f"{k} {v:.1f}" for k, v in mc["buckets_ms"].items())
    gpu = mc.get("gpu_ms", {})
    if isinstance(gpu, dict) and gpu:
        # pt's wavefront lists its stages beside their sum ("render"): count that once.
        frame = gpu["render"] if "render" in gpu else sum(gpu.values())
    gpu_s = ", ".join(f"{k} {v:.1f}" for k, v in gpu.items()) if isinstance(gpu, dict) else ""
    o = d["options"]
    rows.append(f"| {os.path.basename(d['scene']['source']).split('.')[0]} | {o['width']}x{o['height']} | {o['method']} "
                f"| {d['device'].get('setup', {}).get('accel', o.get('accel', '?'))} "
                f"| {frame:.1f} | {stages} | {gpu_s} |")
dev = json.load(open(path))["device"] if rows else {}
lines = [f"device: {dev.get('name', '?')} ({dev.get('driver', '?')})", "",
         "| scene | size | method | accel | frame ms | host stages ms (medians) | device timestamps ms (last run) |",
         "|---|---|---|---|---|---|---|"] + rows + [
    "", "The papers' figures (not measured here):",
    "- SST (Tatzgern et al. 2020, Tables 2-3; RTX 2080 Ti, 1280x720, 1 spp, 100k VPLs, diffuse):",
    "  VPL generation 0.27-0.85 ms, tree building 0.88-0.91 ms, SST sampling 2.65-5.77 ms,",
    "  SLC sampling 3.59-6.83 ms (Living Room: 0.30, 0.89, 2.88, 4.34).",
    "- GI-1.0 (AMD 2022, Table 1; RX 6900 XT, 1920x1080): 1.932-3.124 ms for the whole pipeline."]
if structures:
    mib = lambda b: f"{b / 2**20:.2f}"
    lines += ["", "Ray-tracing structures (the last render of each scene; the flat BVH is built on the host,",
              "the acceleration structures on the device):", "",
              "| scene | triangles | flat BVH build ms | flat BVH MiB | AS build ms (host) | AS build ms (device) "
              "| bottom level MiB | top level MiB | build scratch MiB |", "|---|---|---|---|---|---|---|---|---|"]
    for source, (tris, bvh, acc) in sorted(structures.items()):
        lines.append(f"| {os.path.basename(source).split('.')[0]} | {tris} | {bvh['build_ms']:.1f} | "
                     f"{mib(bvh.get('bytes', 0))} | {acc['build_ms']:.1f} | {acc['build_gpu_ms']:.1f} | "
                     f"{mib(acc['bottom_level_bytes'])} | {mib(acc['top_level_bytes'])} | {mib(acc['scratch_bytes'])} |")
text = "\n".join(lines) + "\n"
open(os.path.join(out, "table.md"), "w").write(text)
print(text)
PY
