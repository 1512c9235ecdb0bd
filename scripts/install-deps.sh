#!/usr/bin/env bash
# Installs sst's build and test dependencies from Debian 12 packages (run as root or with sudo).
# Nothing is downloaded at build time; this is the only install step the README and CI need.
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools libopenexr-dev
  libtinygltf-dev libstb-dev nlohmann-json3-dev libcli11-dev libglm-dev
  libdraco-dev             # glTF KHR_draco_mesh_compression (core/scene/draco_mesh.h)
  libgtest-dev libgmock-dev libbenchmark-dev
  libvulkan-dev glslc vulkan-tools
  parallel
  libkainjow-mustache-dev  # the report's HTML template engine (core/eval/report)
  ffmpeg                   # animated previews (MP4) of rendered sequences
  clang libclang-rt-14-dev llvm  # the fuzz harnesses: libFuzzer, ASan and UBSan runtimes, symbolizer (scripts/fuzz.sh)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The Vulkan driver without a GPU: lavapipe from Mesa 25 (Debian 12's backports suite), which
# has the ray-query extensions, runs sst's kernels 5-10x faster than Mesa 22 and is what current
# distributions ship. The backend still runs on Mesa 22 (scripts/test-mesa22.sh tests it there).
MESA_MIN=25
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
if ! dpkg --compare-versions "${mesa_version:-0}" ge "$MESA_MIN"; then
  if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    printf 'Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' |
      $SUDO tee /etc/apt/sources.list.d/bookworm-backports.sources >/dev/null
  fi
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi
echo "sst: dependencies installed"
