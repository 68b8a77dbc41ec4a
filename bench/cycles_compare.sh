#!/usr/bin/env bash
# shadelab against Blender Cycles (Debian's blender) on one scene: error curves over several spp, each renderer
# against its own converged reference, and the time shadelab needs to reach Cycles' error divided by Cycles'
# time (bench/cycles_curves.py has the method). Without blender it says so and exits 0.
#   bash bench/cycles_compare.sh [SCENE.json] [THREADS] [SPP_LIST] [CONVERGED_SPP] [REPEATS] [OUTDIR]
# defaults: bench/cycles_scene.json, 2 threads, 4,8,16,32,64,128 spp, references at 1024 spp, 2 repetitions.
# SHADELAB=path/to/shadelab overrides the binary (default: the Release build, built if missing); LOCK=file
# is the lock every run takes (default /tmp/shadelab-cpu.lock, the one builds and tests take).
# Cost on 2 cores: about 15 minutes, most of it Cycles' two references.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-bench/cycles_scene.json}
threads=${2:-2}
spps=${3:-4,8,16,32,64,128}
converged=${4:-1024}
repeats=${5:-2}
out=${6:-$(mktemp -d)}
if ! command -v blender > /dev/null; then
  echo "cycles_compare: blender is not installed (apt-get install blender); nothing to compare"
  exit 0
fi
exe=${SHADELAB:-build/release/tools/shadelab/shadelab}
if [ ! -x "$exe" ]; then
  cmake --preset release > /dev/null && cmake --build --preset release --target shadelab_cli > /dev/null
fi
exec /usr/bin/python3 bench/cycles_curves.py "$exe" "$scene" "$threads" "$spps" "$converged" "$repeats" "$out"
