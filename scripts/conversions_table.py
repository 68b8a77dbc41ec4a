#!/usr/bin/python3
"""The tables of docs/conversions.md: `shadelab convert shininess` over n = 1 .. 10^4 (log spaced), for each
source and target, and a paste-able fit of the best roughness with its maximum error.

Usage: /usr/bin/python3 scripts/conversions_table.py [SHADELAB]  (default build/release's, else build/ci's)
Prints Markdown; about 2 CPU-minutes.
"""
import json
import math
import os
import subprocess
import sys

exe = sys.argv[1] if len(sys.argv) > 1 else next(
    (c for c in ("build/release/tools/shadelab/shadelab", "build/ci/tools/shadelab/shadelab") if os.access(c, os.X_OK)), None)
if exe is None:
    sys.exit("conversions_table: no shadelab executable (build first, or give its path)")

NS = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000]
PAIRS = [("blinn-phong", "ggx"), ("phong", "ggx"), ("blinn-phong-modified", "ggx"), ("blinn-phong-microfacet", "beckmann"),
         ("blinn-phong", "beckmann")]


def convert(src, dst, n):
    out = subprocess.run([exe, "convert", "shininess", "--from", src, "--to", dst, "--n", str(n), "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def fmt_map(m):
    if m["alpha"] is None:
        return "undefined"
    return "%.4g (%.1f%%)" % (m["alpha"], 100 * m["relative_residual"])


results = {}
for src, dst in PAIRS:
    print("\n#### %s -> %s\n" % (src, dst))
    print("| n | best alpha | best roughness | residual / lobe | walter alpha (residual / lobe) | cod | godot | babylon |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    rows = []
    for n in NS:
        j = convert(src, dst, n)
        rows.append((n, j["alpha"]))
        maps = {m["name"]: m for m in j["mappings"]}
        print("| %g | %.4g%s | %.4f | %.1f%% | %s | %s | %s | %s |" % (
            n, j["alpha"], " (range end)" if j["at_bound"] else "", j["roughness"], 100 * j["relative_residual"],
            fmt_map(maps["walter"]), fmt_map(maps["cod"]), fmt_map(maps["godot"]), fmt_map(maps["babylon"])))
    results[(src, dst)] = rows

# A paste-able fit of the optimum: alpha = sqrt(a / (n + b)), Walter's form with its constants refitted, by least
# squares on log(alpha) over a fine grid of (a, b); its maximum relative error over the table's n.
print("\n#### Paste-able fits of the best alpha: alpha = sqrt(a / (n + b))\n")
print("| source -> target | a | b | max. relative error of alpha over n = 1 .. 10^4 |")
print("| --- | --- | --- | --- |")
for (src, dst), rows in results.items():
    best = None
    for ia in range(1, 801):
        a = ia * 0.01
        for ib in range(0, 401):
            b = ib * 0.025
            err = max(abs(math.sqrt(a / (n + b)) / al - 1) for n, al in rows)
            if best is None or err < best[0]:
                best = (err, a, b)
    print("| %s -> %s | %.2f | %.3f | %.1f%% |" % (src, dst, best[1], best[2], 100 * best[0]))
