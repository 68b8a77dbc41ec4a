#!/usr/bin/env python3
# Error curves of shadelab and Blender Cycles on one scene, and the time each needs to reach an error; run by
# bench/cycles_compare.sh (which says what it needs). Standard library only.
#
# Method (issue 15):
# - Each renderer is scored against its OWN converged reference (two references per renderer, at CONVERGED spp
#   with different seeds). The references' own noise is removed from every MSE: MSE(image, ref_a) estimates
#   MSE_true + var_ref, and var_ref = MSE(ref_a, ref_b) / 2 (independent references of equal variance).
# - Same scene, bounce count and pixel filter (bench/cycles_compare.py says how), same thread count.
# - Times: whole process (wall clock of `shadelab render` / `blender -b`, start-up, scene loading and file
#   writing included) and render time without scene synchronisation (shadelab: JSON render_seconds; Cycles:
#   its progress lines from "Sample 0/N" to "Finished").
# - Every run holds the CPU lock (LOCK, default /tmp/shadelab-cpu.lock) alone, shadelab and Cycles alternate
#   at each spp, REPEATS times; the fastest repetition counts (the one least disturbed by other load).
# - Curves: RMSE against spp for both, the fitted slope of log RMSE on log spp, and for each of Cycles' points
#   the time shadelab needs to reach the same RMSE (log-log interpolation of shadelab's curve, extrapolation
#   by its fitted power law outside it), divided by Cycles' time there.
# - Per sphere (issue 10): the ratio of the two converged references' means over the pixels that see only
#   that sphere (bench/cycles_spheres.py), so the GGX spheres are checked material by material.
import fcntl
import json
import math
import os
import re
import subprocess
import sys
import time


def main():
    if len(sys.argv) < 7:
        sys.exit("usage: cycles_curves.py SHADELAB SCENE THREADS SPP_LIST CONVERGED_SPP REPEATS [OUTDIR]")
    exe, scene, threads = sys.argv[1], sys.argv[2], int(sys.argv[3])
    spps = [int(x) for x in sys.argv[4].split(",")]
    converged, repeats = int(sys.argv[5]), int(sys.argv[6])
    out = sys.argv[7] if len(sys.argv) > 7 else "/tmp/cycles_compare"
    os.makedirs(out, exist_ok=True)
    lock_path = os.environ.get("LOCK", "/tmp/shadelab-cpu.lock")
    here = os.path.dirname(os.path.abspath(__file__))

    def locked(cmd):
        with open(lock_path, "a") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            t0 = time.monotonic()
            p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            wall = time.monotonic() - t0
            fcntl.flock(lock, fcntl.LOCK_UN)
        if p.returncode != 0:
            sys.exit("cycles_compare: %s failed:\n%s" % (" ".join(cmd), p.stdout[-3000:]))
        return wall, p.stdout

    def shadelab(spp, seed, path):
        wall, text = locked([exe, "render", scene, "--spp", str(spp), "--threads", str(threads), "--seed", str(seed),
                             "--no-png", "--out", path, "--json"])
        j = json.loads(text[text.index("{"):])
        return {"process": wall, "render": j["render_seconds"]}

    def cycles(spp, seed, path):
        wall, text = locked(["blender", "-b", "--factory-startup", "--python", os.path.join(here, "cycles_compare.py"),
                             "--", scene, str(spp), path, str(threads), str(seed)])
        stamps = {}
        for line in text.splitlines():
            m = re.search(r"\| Time:(\d+):(\d+\.\d+) .*\| (Sample 0/\d+|Finished)", line)
            if m:
                key = "start" if m.group(3).startswith("Sample") else "end"
                stamps.setdefault(key, int(m.group(1)) * 60 + float(m.group(2)))
        result = json.loads(text.split("CYCLES_RESULT ", 1)[1].splitlines()[0])
        return {"process": wall, "render": stamps["end"] - stamps["start"], "pattern": result["sampling_pattern"]}

    def compare(a, b):
        p = subprocess.run([exe, "compare", a, b, "--ignore-alpha", "--json"], stdout=subprocess.PIPE, text=True, check=True)
        return json.loads(p.stdout)

    renderers = {"shadelab": shadelab, "cycles": cycles}
    print("cycles_compare: %s, %d threads, spp %s, references at %d spp (2 seeds each), %d repetitions"
          % (scene, threads, spps, converged, repeats), flush=True)
    refs = {}
    info = {}
    for name, run in renderers.items():
        for seed in (1, 2):
            path = os.path.join(out, "%s_ref%d.exr" % (name, seed))
            info[name] = run(converged, 100 + seed, path)
            refs.setdefault(name, []).append(path)
        print("  %s references done (%.0f s each)" % (name, info[name]["process"]), flush=True)
    ref_var = {}
    for name in renderers:
        c = compare(refs[name][0], refs[name][1])
        ref_var[name] = c["rmse"] ** 2 / 2.0
    agreement = compare(refs["shadelab"][0], refs["cycles"][0])
    # Per-sphere mean ratios of the converged references (bench/cycles_spheres.py, in Blender's Python).
    p = subprocess.run(["blender", "-b", "--factory-startup", "--python", os.path.join(here, "cycles_spheres.py"), "--",
                        scene, refs["shadelab"][0], refs["cycles"][0]], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    spheres = json.loads(p.stdout.split("SPHERES_RESULT ", 1)[1].splitlines()[0]) if "SPHERES_RESULT " in p.stdout else []

    curves = {name: [] for name in renderers}
    for spp in spps:
        best = {name: None for name in renderers}
        for _ in range(repeats):
            for name, run in renderers.items():  # alternate the two renderers
                path = os.path.join(out, "%s_%d.exr" % (name, spp))
                t = run(spp, 1, path)
                if best[name] is None or t["render"] < best[name]["render"]:
                    best[name] = t
        for name in renderers:
            c = compare(os.path.join(out, "%s_%d.exr" % (name, spp)), refs[name][0])
            mse = max(c["rmse"] ** 2 - ref_var[name], 1e-30)
            curves[name].append({"spp": spp, "rmse": math.sqrt(mse), "relmse": c["relative_mse"],
                                 "render": best[name]["render"], "process": best[name]["process"]})
        print("  %4d spp: shadelab RMSE %.4g in %.3g s, cycles RMSE %.4g in %.3g s"
              % (spp, curves["shadelab"][-1]["rmse"], curves["shadelab"][-1]["render"],
                 curves["cycles"][-1]["rmse"], curves["cycles"][-1]["render"]), flush=True)

    def fit(xs, ys):  # least squares on logs: log y = a + b log x
        lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
        mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
        b = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)
        return my - b * mx, b

    def time_to_reach(curve, key, error):
        pts = sorted((p[key], p["rmse"]) for p in curve)
        for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
            if e1 <= error <= e0:
                f = math.log(e0 / error) / math.log(e0 / e1)
                return math.exp(math.log(t0) + f * math.log(t1 / t0)), "interpolated"
        a, b = fit([p[0] for p in pts], [p[1] for p in pts])
        return math.exp((math.log(error) - a) / b), "extrapolated"

    report = {"scene": scene, "threads": threads, "converged_spp": converged, "reference_rmse": {n: math.sqrt(v) for n, v in ref_var.items()},
              "cycles_sampling_pattern": info["cycles"]["pattern"], "curves": curves,
              "references_mean_luminance_ratio": agreement["mean_luminance_ratio"]}
    print()
    print("Each renderer against its own converged reference (%d spp; reference noise removed)." % converged)
    print("Converged shadelab / Cycles mean luminance: %.5f (independent renderers, same scene)"
          % agreement["mean_luminance_ratio"])
    print("Cycles sampling pattern: %s" % info["cycles"]["pattern"])
    report["sphere_mean_ratios"] = spheres
    for sp in spheres:
        print("  sphere %d (%s): shadelab / Cycles mean %.5f over %d pixels" % (sp["shape"], sp["material"], sp["ratio"], sp["pixels"]))
    print("%5s | %10s %9s %9s | %10s %9s %9s" % ("spp", "shadelab", "render s", "process s", "cycles", "render s", "process s"))
    for s, c in zip(curves["shadelab"], curves["cycles"]):
        print("%5d | %10.4g %9.3g %9.3g | %10.4g %9.3g %9.3g" % (s["spp"], s["rmse"], s["render"], s["process"],
                                                              c["rmse"], c["render"], c["process"]))
    slopes = {}
    for name in renderers:
        _, b = fit([p["spp"] for p in curves[name]], [p["rmse"] for p in curves[name]])
        _, br = fit([p["spp"] for p in curves[name]], [p["relmse"] for p in curves[name]])
        slopes[name] = {"rmse": b, "relmse": br}
        print("%-8s RMSE ~ spp^%.3f, relMSE ~ spp^%.3f" % (name, b, br))
    report["slopes"] = slopes
    print()
    print("Time shadelab needs to reach Cycles' RMSE, divided by Cycles' time (target <= 0.5):")
    print("%5s %10s %12s %12s" % ("spp", "RMSE", "render-only", "whole process"))
    ratios = []
    for c in curves["cycles"]:
        tr, how_r = time_to_reach(curves["shadelab"], "render", c["rmse"])
        tp, how_p = time_to_reach(curves["shadelab"], "process", c["rmse"])
        ratios.append({"spp": c["spp"], "rmse": c["rmse"], "render_ratio": tr / c["render"], "process_ratio": tp / c["process"],
                       "render_how": how_r, "process_how": how_p})
        print("%5d %10.4g %12.3f %12.3f%s" % (c["spp"], c["rmse"], tr / c["render"], tp / c["process"],
                                               "" if how_r == "interpolated" else "  (shadelab curve extrapolated)"))
    report["time_ratios"] = ratios
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=1)
    print("images and report.json in", out)


if __name__ == "__main__":
    main()
