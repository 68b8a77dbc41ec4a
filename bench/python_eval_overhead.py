#!/usr/bin/env python3
"""Overhead of shadelab.Brdf.eval from Python on N direction pairs, against the same work in C++.

Both sides evaluate the same N unit-length pairs (written to a file for the C++ program), single-threaded,
for every registered model. The C++ side (bench/python_eval_baseline.cpp, Google Benchmark) measures the
two plain ways to do it with the library: Brdf::eval_batch over the arrays (the best) and the loop of
per-pair eval calls; and, as a column, eval_batch_checked (the same batch checking that each direction is
unit length), which Python's eval calls on the arrays in place. The sides are alternated ROUNDS times in
one run, and each ratio is Python's best CPU time over C++'s best CPU time over all rounds (CPU time,
which other processes on a shared machine distort least; the best time, which they can only lengthen),
with the median of the per-round ratios beside it. A benchmark, not a test: timings on a shared machine
vary, the ratio measured in one run is what means something (shared/design/PERFORMANCE.md).

    cmake --build --preset release --target shadelab_python python_eval_baseline
    /usr/bin/python3 bench/python_eval_overhead.py --build build/release

Python's eval does what the C++ calls do not: converts the arrays (no copy for C-contiguous float64),
checks each direction as the CLI does (unit directions are used in place, checked inside the library's
loop; from the first that is not, a chunk is copied and normalized), and allocates the (N, 3) result unless out= is given (the C++ output is allocated once, so
out= is the like-for-like figure). Both are reported.
"""
import argparse
import json
import os
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
    print(f"shadelab {shadelab.__version__}: Brdf.eval on {n} pairs, Python (this process) vs C++ ({baseline.name}: "
          f"eval_batch and the per-pair eval loop); CPU ms, best of {args.repeats} calls per round, {args.rounds} rounds; "
          f"ratio = Python / C++ (best over rounds), median of per-round ratios in parentheses")
    print(f"{'model':<26} {'batch ms':>9} {'loop ms':>8} {'checked':>8} {'eval ms':>8} {'/batch':>14} {'/loop':>14} "
          f"{'out= ms':>8} {'/batch':>14} {'/loop':>14}")
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
            batch, loop, checked, py, py_out = [], [], [], [], []
            for _ in range(args.rounds):
                r = subprocess.run([str(baseline), f"--benchmark_repetitions={args.repeats}",
                                    "--benchmark_format=json", "--benchmark_min_time=0.05"],
                                   env=env, capture_output=True, text=True, check=True)
                runs = [b for b in json.loads(r.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
                # ms (Unit(kMillisecond))
                batch.append(min(b["cpu_time"] for b in runs if b["run_name"].startswith("eval_batch/")))
                loop.append(min(b["cpu_time"] for b in runs if b["run_name"].startswith("eval_loop/")))
                checked.append(min(b["cpu_time"] for b in runs if b["run_name"].startswith("eval_batch_checked/")))
                py.append(best_ms(lambda: f.eval(wi, wo), args.repeats))
                py_out.append(best_ms(lambda: f.eval(wi, wo, out=out), args.repeats))
            assert np.array_equal(f.eval(wi, wo), out)

            def ratio(p, c):
                return f"{min(p) / min(c):6.3f} ({statistics.median(a / b for a, b in zip(p, c)):5.3f})"

            label = model + "".join(f" {k}={v}" for k, v in params.items())
            print(f"{label:<26} {min(batch):9.2f} {min(loop):8.2f} {min(checked):8.2f} {min(py):8.2f} {ratio(py, batch):>14} "
                  f"{ratio(py, loop):>14} {min(py_out):8.2f} {ratio(py_out, batch):>14} {ratio(py_out, loop):>14}",
                  flush=True)


def best_ms(call, repeats):
    call()  # warm: page in the arrays, first-touch the result pages
    best = float("inf")
    for _ in range(repeats):
        t0 = time.thread_time()  # CPU time of this thread, as Google Benchmark's cpu_time
        call()
        best = min(best, time.thread_time() - t0)
    return best * 1e3


if __name__ == "__main__":
    main()
