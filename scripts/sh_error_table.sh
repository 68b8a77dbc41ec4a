#!/usr/bin/env bash
# The SH-family irradiance error table of docs/envmap.md: `shadelab bake sh MAP --error-report --json` on each
# of Blender's eight studio-light worlds (Debian's blender-data), formatted as Markdown (cells: mean / max
# relative error of the luminance of E, in %, and the solid angle in sr where the encoding goes negative).
# Usage: scripts/sh_error_table.sh [SHADELAB_BINARY] [WORLDS_DIR]
set -euo pipefail
exe=${1:-build/ci/tools/shadelab/shadelab}
dir=${2:-/usr/share/blender/datafiles/studiolights/world}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for name in city courtyard forest interior night studio sunrise sunset; do
  "$exe" bake sh "$dir/$name.exr" --error-report --json > "$tmp/$name.json"
done
/usr/bin/python3 - "$tmp" <<'PY'
import json, sys, os
tmp = sys.argv[1]
names = ["city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"]
reports = {n: json.load(open(os.path.join(tmp, n + ".json")))["error_report"] for n in names}
first = reports[names[0]]
print(f"Environment cube {first['environment_face_size']}^2 per face, exact irradiance at {first['evaluation_face_size']}^2 per face.")
print()
print("| encoding | coeffs | " + " | ".join(names) + " |")
print("|---|---|" + "---|" * len(names))
for i, row in enumerate(first["encodings"]):
    cells = []
    for n in names:
        r = reports[n]["encodings"][i]
        assert r["encoding"] == row["encoding"]
        neg = r["negative_solid_angle_sr"]
        cells.append(f"{100 * r['mean_relative_error']:.1f} / {100 * r['max_relative_error']:.0f}" + (f" / **{neg:.2f}**" if neg > 0 else " / 0"))
    print(f"| {row['encoding']} | {row['coefficients_per_channel']} | " + " | ".join(cells) + " |")
PY
