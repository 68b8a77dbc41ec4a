#!/usr/bin/env python3
"""Overhead of shadelab.Brdf.eval from Python on N direction pairs, against the same work in C++.

Both sides evaluate the same N unit-length pairs (written to a file for the C++ program), single-threaded,
for every registered model. The C++ side (bench/python_eval_baseline.cpp, Google Benchmark) measures the
two plain ways to do it with the library, Brdf::eval_batch over the arrays (the best) and the loop of
per-pair eval calls, each twice: with the output allocated once (batch, loop) and with a new output
allocated per call as NumPy allocates Python's result (bfresh, lfresh); eval_batch_checked (the entry
Python's eval calls on the arrays in place) is a column for the record. Like for like: plain `eval`
(a new result per call) against bfresh / lfresh, `eval(..., out=)` against batch / loop. The sides are
alternated ROUNDS times in one run; in each round each side's time is its best CPU time of REPEATS calls
(CPU time, which other processes on a shared machine distort least; the best, which they can only
lengthen), and each ratio is reported as the median of the per-round ratios with their range. The minor
page faults per call of Python's eval and of C++'s eval_batch_fresh are printed too, to show whether the
fresh result was paged in anew on either side. A benchmark, not a test: timings on a shared machine vary,
the ratio measured in one run is what means something (shared/design/PERFORMANCE.md).

    cmake --build --preset release --target shadelab_python python_eval_baseline
    /usr/bin/python3 bench/python_eval_overhead.py --build build/release

Python's eval does what the C++ calls do not: converts the arrays (no copy for C-contiguous float64) and
checks each direction as the CLI does (unit directions are used in place, checked inside the library's
loop; from the first that is not, a chunk is copied and normalized).
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# Non-default parameters where the last report used them; every other registered model at its defaults.
PARAMS = {"blinn-phong-modified": {"n": 200}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build/release", help="CMake build folder (default build/release)")
    ap.add_argument("--pairs", type=float, default=1e6, help="direction pairs per call (default 1e6)")
    ap.add_argument("--rounds", type=int, default=3, help="alternations of C++ and Python (default 3)")
    ap.add_argument("--repeats", type=int, default=7, help="timed calls per round on each side (default 7)")
    ap.add_argument("--model", action="append", help="a model to measure (repeatable; default: every registered model)")
    args = ap.parse_args()

    build = Path(args.build).resolve()
    sys.path.insert(0, str(build / "python" / "site"))
    import shadelab  # noqa: E402  (the module of this build, not an installed one)

    baseline = build / "bench" / "python_eval_baseline"
    if not baseline.exists():
        sys.exit(f"{baseline} not found: build the python_eval_baseline target")
    n = int(args.pairs)
    rng = np.random.default_rng(2024)

    def cosine_hemisphere(k):  # cosine-weighted directions, the mix bench/brdf_bench.cpp uses
        u1, u2 = rng.random(k), rng.random(k)
        r, phi = np.sqrt(u1), 2 * np.pi * u2
        v = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(0.0, 1 - u1))], axis=1)
        return v / np.linalg.norm(v, axis=1, keepdims=True)

    wi = np.ascontiguousarray(cosine_hemisphere(n))
    wo = np.ascontiguousarray(cosine_hemisphere(n))
    names = args.model or [m["name"] for m in shadelab.models()]
    models = [(m, PARAMS.get(m, {})) for m in names]
    print(f"shadelab {shadelab.__version__}: Brdf.eval on {n} pairs, Python (this process) vs C++ ({baseline.name}); "
          f"CPU ms, best of {args.repeats} calls per round, {args.rounds} rounds (the best over rounds shown). "
          f"Ratios: per round, Python's best / C++'s best in that round; the median over rounds [lowest-highest]. "
          f"eval (a new result per call) against the C++ loops that allocate their output per call (bfresh, lfresh); "
          f"eval(out=) against the loops with the output allocated once (batch, loop); eval/cfresh and out=/checked: "
          f"against the very C++ call Python's eval makes (eval_batch_checked, output fresh or reused). flt: minor page faults per "
          f"call, Python's eval / C++'s eval_batch_fresh (0: the freed result block was handed back without paging)")
    print(f"{'model':<26} {'batch':>7} {'loop':>7} {'checked':>7} {'bfresh':>7} {'lfresh':>7} {'eval':>7} "
          f"{'eval/bfresh':>19} {'eval/lfresh':>19} {'out=':>7} {'out=/batch':>19} {'out=/loop':>19} {'flt':>9}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        pairs_file = Path(tmp) / "pairs.bin"
        with open(pairs_file, "wb") as fh:
            fh.write(wi.tobytes())
            fh.write(wo.tobytes())
        for model, params in models:
            f = shadelab.Brdf(model, **params)
            out = np.empty((n, 3))
            env = dict(os.environ, SHADELAB_BENCH_PAIRS=str(pairs_file), SHADELAB_BENCH_MODEL=model,
                       SHADELAB_BENCH_PARAMS=";".join(f"{k}={v}" for k, v in params.items()))
            cpp = {k: [] for k in ("eval_batch", "eval_loop", "eval_batch_checked", "eval_batch_fresh", "eval_loop_fresh",
                                        "eval_checked_fresh")}
            cpp_faults = []
            py, py_out, py_faults = [], [], []
            for _ in range(args.rounds):
                r = subprocess.run([str(baseline), f"--benchmark_repetitions={args.repeats}",
                                    "--benchmark_format=json", "--benchmark_min_time=0.05"],
                                   env=env, capture_output=True, text=True, check=True)
                runs = [b for b in json.loads(r.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
                for key, times in cpp.items():  # ms (Unit(kMillisecond)); run_name is "KEY/MODEL"
                    times.append(min(b["cpu_time"] for b in runs if b["run_name"].split("/")[0] == key))
                cpp_faults.append(statistics.median(b["faults"] for b in runs
                                                    if b["run_name"].split("/")[0] == "eval_batch_fresh"))
                t, flt = best_ms(lambda: f.eval(wi, wo), args.repeats)
                py.append(t)
                py_faults.append(flt)
                py_out.append(best_ms(lambda: f.eval(wi, wo, out=out), args.repeats)[0])
            assert np.array_equal(f.eval(wi, wo), out)

            def ratio(p, c):
                per_round = [a / b for a, b in zip(p, c)]
                return (statistics.median(per_round), min(per_round), max(per_round))

            def text(rt):
                return f"{rt[0]:5.3f} [{rt[1]:5.3f}-{rt[2]:5.3f}]"

            label = model + "".join(f" {k}={v}" for k, v in params.items())
            ratios = [ratio(py, cpp["eval_batch_fresh"]), ratio(py, cpp["eval_loop_fresh"]),
                      ratio(py_out, cpp["eval_batch"]), ratio(py_out, cpp["eval_loop"]),
                      ratio(py, cpp["eval_checked_fresh"]), ratio(py_out, cpp["eval_batch_checked"])]
            rows.append((label, ratios))
            ms = " ".join(f"{min(cpp[k]):7.2f}" for k in ("eval_batch", "eval_loop", "eval_batch_checked",
                                                          "eval_batch_fresh", "eval_loop_fresh"))
            flt = f"{statistics.median(py_faults):.0f}/{statistics.median(cpp_faults):.0f}"
            print(f"{label:<26} {ms} {min(py):7.2f} {text(ratios[0]):>19} {text(ratios[1]):>19} {min(py_out):7.2f} "
                  f"{text(ratios[2]):>19} {text(ratios[3]):>19} {flt:>9} {text(ratios[4]):>19} {text(ratios[5]):>19}", flush=True)
    names = ["eval/bfresh", "eval/lfresh", "out=/batch", "out=/loop", "eval/cfresh", "out=/checked"]
    for i, name in enumerate(names):
        medians = [r[i][0] for _, r in rows]
        over = [f"{label} {r[i][0]:.3f}" for label, r in rows if r[i][0] > 1.10]
        print(f"{name}: median ratio within 1.10 for {len(rows) - len(over)} of {len(rows)} models, "
              f"median over models {statistics.median(medians):.3f}" + (f"; above: {', '.join(over)}" if over else ""))


def best_ms(call, repeats):
    """The best CPU time of `repeats` calls in ms, and the median minor page faults per call."""
    call()  # warm: page in the arrays, first-touch the result pages
    best = float("inf")
    faults = []
    for _ in range(repeats):
        f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        t0 = time.thread_time()  # CPU time of this thread, as Google Benchmark's cpu_time
        call()
        t1 = time.thread_time()
        faults.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
        best = min(best, t1 - t0)
    return best * 1e3, statistics.median(faults)


if __name__ == "__main__":
    main()
