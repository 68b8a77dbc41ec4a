#!/usr/bin/env bash
# Renders one scene with shadelab and with Blender Cycles (Debian's blender) at the same samples per pixel and
# reports both renderers' samples per second and their RMSE against a converged shadelab image, so the two
# can be compared at equal quality. Without blender it says so and exits 0.
#   bash bench/cycles_compare.sh [SCENE.json] [SPP] [THREADS] [CONVERGED_SPP]
# SHADELAB=path/to/shadelab overrides the binary (default: the Release build, built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-bench/cycles_scene.json}
spp=${2:-64}
threads=${3:-2}
converged=${4:-2048}
if ! command -v blender > /dev/null; then
  echo "cycles_compare: blender is not installed (apt-get install blender); nothing to compare"
  exit 0
fi
exe=${SHADELAB:-build/release/tools/shadelab/shadelab}
if [ ! -x "$exe" ]; then
  cmake --preset release > /dev/null && cmake --build --preset release --target shadelab_cli > /dev/null
fi
out=$(mktemp -d)
"$exe" render "$scene" --spp "$converged" --threads "$threads" --no-png --out "$out/converged.exr" --json > "$out/converged.json"
"$exe" render "$scene" --spp "$spp" --threads "$threads" --no-png --out "$out/shadelab.exr" --json > "$out/shadelab.json"
blender -b --factory-startup --python bench/cycles_compare.py -- "$scene" "$spp" "$out/cycles.exr" "$threads" \
  > "$out/cycles.log" 2>&1 || { tail -20 "$out/cycles.log"; exit 1; }
"$exe" compare "$out/shadelab.exr" "$out/converged.exr" --json > "$out/shadelab_vs_converged.json"
"$exe" compare "$out/cycles.exr" "$out/converged.exr" --ignore-alpha --json > "$out/cycles_vs_converged.json"
python3 - "$out" "$spp" "$converged" <<'PY'
import json, sys
out, spp, converged = sys.argv[1], sys.argv[2], sys.argv[3]
s = json.load(open(out + "/shadelab.json"))
c = [json.loads(l.split("CYCLES_RESULT ", 1)[1]) for l in open(out + "/cycles.log") if "CYCLES_RESULT" in l][0]
ds = json.load(open(out + "/shadelab_vs_converged.json"))
dc = json.load(open(out + "/cycles_vs_converged.json"))
print("%s spp each; reference: shadelab at %s spp" % (spp, converged))
print("%-9s %12s %10s %10s %12s" % ("renderer", "samples/s", "RMSE", "relMSE", "lum. ratio"))
print("%-9s %12.4g %10.4g %10.4g %12.4f" % ("shadelab", s["samples_per_second"], ds["rmse"], ds["relative_mse"], ds["mean_luminance_ratio"]))
print("%-9s %12.4g %10.4g %10.4g %12.4f" % ("cycles", c["samples_per_second"], dc["rmse"], dc["relative_mse"], dc["mean_luminance_ratio"]))
print("files in", out)
PY
