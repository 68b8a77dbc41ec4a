#!/bin/bash
# The table of docs/models/layering.md: `shadelab layering-error gltf` over base x clearcoat roughness (clearcoat 1).
# Usage: bash scripts/layering_table.sh [SHADELAB] (default build/release/tools/shadelab/shadelab, else build/ci's).
# Prints the Markdown table; about 1 CPU-minute.
set -euo pipefail
exe=${1:-}
if [ -z "$exe" ]; then
  for c in build/release/tools/shadelab/shadelab build/ci/tools/shadelab/shadelab; do [ -x "$c" ] && exe=$c && break; done
fi
[ -x "$exe" ] || { echo "layering_table: no shadelab executable (build first, or give its path)" >&2; exit 2; }
py=/usr/bin/python3
echo "| base | coat roughness | albedo diff., glTF | albedo diff., albedo-scaled | lobe RMSE / truth RMS, glTF | the same, albedo-scaled | truth noise / RMS | truth s.e. | truth's white furnace |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for base in "lambert 0.8" "lambert 0.2" "gold 0.3" "silver 0.6"; do
  set -- $base
  case $1 in
    lambert) bp="--param metallic=0 --param specular=0 --param base_color=$2"; name="Lambert $2";;
    gold) bp="--param metallic=1 --param base_color=1,0.78,0.34 --param roughness=$2"; name="gold metal, roughness $2";;
    silver) bp="--param metallic=1 --param base_color=0.97,0.96,0.91 --param roughness=$2"; name="silver metal, roughness $2";;
  esac
  for cr in 0.03 0.3 0.6 1.0; do
    # shellcheck disable=SC2086
    "$exe" layering-error gltf $bp --param clearcoat=1 --param clearcoat_roughness=$cr --walks 32 --samples 100000 --json |
      "$py" -c '
import json, sys
j = json.load(sys.stdin); a = j["albedo"]; l = j["lobe"]
def worst(k):
    r = max(a, key=lambda x: abs(x[k] - x["truth"])); return "%+.3f (%d deg)" % (r[k] - r["truth"], r["theta"])
rel = lambda k: max(x[k] / x["truth_rms"] for x in l)
print("| %s | %s | %s | %s | %.2f | %.2f | %.3f | %.4f | %.3f |" % (sys.argv[1], sys.argv[2], worst("model"), worst("albedo_scaled"),
      rel("model_rmse"), rel("albedo_scaled_rmse"), max(x["truth_noise_rms"] / x["truth_rms"] for x in l),
      max(x["truth_error"] for x in a), a[0]["truth_furnace"]))' "$name" "$cr"
  done
done
