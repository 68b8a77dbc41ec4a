#!/usr/bin/env bash
# Installs every Debian 12 package shadelab needs to build, test and benchmark.
# Idempotent and non-interactive: packages already present are left as they are.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libopenexr-dev libstb-dev libtbb-dev
  libnlopt-dev
  libopencolorio-dev
  opencolorio-tools
  libcairo2-dev fonts-dejavu-core
  libembree-dev libtinyobjloader-dev libtinygltf-dev
  blender-data
  glslang-tools spirv-tools mesa-vulkan-drivers libvulkan-dev chromium
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-jsonschema
  parallel slurm-wlm slurm-client munge
  emscripten
  clang-14 libclang-rt-14-dev llvm-14
)

# The independent KTX 2 reader of the container tests (tools/containers): npm's ktx-parse, pinned by its
# package-lock.json; `npm ls` (offline) says whether the pinned version is already there.
containers="$(cd "$(dirname "$0")/.." && pwd)/tools/containers"
if ! npm ls --prefix "$containers" ktx-parse >/dev/null 2>&1; then
  echo "setup: npm ci in tools/containers"
  (cd "$containers" && npm ci --no-audit --no-fund)
fi

# The peer of `convert gltf` (tools/gltf_transform): npm's @gltf-transform/core, /extensions and /functions, pinned
# by its package-lock.json; the CLI test runs its metalRough() with node.
gltf_transform="$(cd "$(dirname "$0")/.." && pwd)/tools/gltf_transform"
if ! npm ls --prefix "$gltf_transform" @gltf-transform/functions >/dev/null 2>&1; then
  echo "setup: npm ci in tools/gltf_transform"
  (cd "$gltf_transform" && npm ci --no-audit --no-fund)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -q
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The explorer's browser tests: playwright-core pinned in tools/explore/test/package-lock.json (it drives
# Debian's chromium; it downloads no browser). Node.js is the machine's (Debian's nodejs where it has none).
explore_tests="$(dirname "$0")/../tools/explore/test"
if ! command -v npm >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends nodejs npm
fi
if [ ! -f "$explore_tests/node_modules/.package-lock.json" ] ||
   [ "$explore_tests/package-lock.json" -nt "$explore_tests/node_modules/.package-lock.json" ]; then
  (cd "$explore_tests" && npm ci --no-audit --no-fund)
fi
