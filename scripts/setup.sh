#!/usr/bin/env bash
# Installs every Debian 12 package shadelab needs to build, test and benchmark.
# Idempotent and non-interactive: packages already present are left as they are.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libopenexr-dev libstb-dev libtbb-dev
  libcairo2-dev fonts-dejavu-core
  libembree-dev libtinyobjloader-dev libtinygltf-dev
  blender-data
  glslang-tools spirv-tools mesa-vulkan-drivers libvulkan-dev chromium
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
  clang-14 libclang-rt-14-dev llvm-14
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -q
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
