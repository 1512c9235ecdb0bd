#!/usr/bin/env bash
# Runs the Vulkan tests (ctest label `gpu`) on Mesa 22's lavapipe, the driver Debian 12 itself
# ships, while the machine keeps Mesa 25 (scripts/install-deps.sh) as its own: the bookworm
# package is downloaded and unpacked into <build>/mesa22 (not installed) and chosen through
# VK_ICD_FILENAMES, with a shader cache of its own. Usage: scripts/test-mesa22.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
dir=$PWD/$build/mesa22
if [ ! -f "$dir/icd.json" ]; then
  rm -rf "$dir" && mkdir -p "$dir"
  (cd "$dir" && apt-get download -qq mesa-vulkan-drivers/bookworm 2>/dev/null)
  dpkg -x "$dir"/mesa-vulkan-drivers_*.deb "$dir/root"
  lib=$(find "$dir/root" -name libvulkan_lvp.so | head -1)
  printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.1.0"}}\n' "$lib" \
    > "$dir/icd.json"
fi
export VK_ICD_FILENAMES=$dir/icd.json MESA_SHADER_CACHE_DIR=$dir/shader-cache
vulkaninfo --summary 2>/dev/null | grep -m1 driverInfo || { echo "test-mesa22: Mesa 22's lavapipe does not load" >&2; exit 1; }
ctest --test-dir "$build" -L gpu --output-on-failure -j2
