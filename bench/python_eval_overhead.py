#!/usr/bin/env python3
"""Overhead of shadelab.Brdf.eval from Python on N direction pairs, against the same C++ loop.

Both sides evaluate the same N unit-length pairs (written to a file for the C++ program), single-threaded;
the two are alternated ROUNDS times in one run, and the ratio reported is Python's best CPU time over
C++'s best CPU time over all rounds (CPU time, which other processes on a shared machine distort least;
the best time, which they can only lengthen), with the median of the per-round ratios beside it. A benchmark, not a test: timings on a shared machine vary, the
ratio measured in one run is what means something (shared/design/PERFORMANCE.md).

    cmake --build --preset release --target shadelab_python python_eval_baseline
    /usr/bin/python3 bench/python_eval_overhead.py --build build/release

Python's eval does what the C++ loop does not: converts the arrays (no copy for C-contiguous float64),
checks and normalizes each direction as the CLI does (one square root per direction; the division is
skipped for unit vectors), and allocates the (N, 3) result unless out= is given. Both are reported.
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

MODELS = [("cook-torrance", {}), ("blinn-phong-modified", {"n": 200}), ("ward-anisotropic", {}), ("lambert", {})]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build/release", help="CMake build folder (default build/release)")
    ap.add_argument("--pairs", type=float, default=1e6, help="direction pairs per call (default 1e6)")
    ap.add_argument("--rounds", type=int, default=3, help="alternations of C++ and Python (default 3)")
    ap.add_argument("--repeats", type=int, default=7, help="timed calls per round on each side (default 7)")
    ap.add_argument("--model", action="append", help="models to measure (default: %s)" % ", ".join(m for m, _ in MODELS))
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
    models = [(m, dict(MODELS).get(m, {})) for m in args.model] if args.model else MODELS
    print(f"shadelab {shadelab.__version__}: Brdf.eval on {n} pairs, Python (this process) vs the C++ loop "
          f"({baseline.name}); best of {args.repeats} calls per round, median of {args.rounds} rounds")
    print(f"{'model':<24} {'C++ ms':>8} {'Python ms':>10} {'ratio':>6} {'(median)':>9} {'out= ms':>8} {'ratio':>6} {'(median)':>9}")
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
            cpp, py, py_out = [], [], []
            for _ in range(args.rounds):
                r = subprocess.run([str(baseline), f"--benchmark_repetitions={args.repeats}",
                                    "--benchmark_format=json", "--benchmark_min_time=0.05"],
                                   env=env, capture_output=True, text=True, check=True)
                runs = [b for b in json.loads(r.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
                cpp.append(min(b["cpu_time"] for b in runs))  # ms (Unit(kMillisecond))
                py.append(best_ms(lambda: f.eval(wi, wo), args.repeats))
                py_out.append(best_ms(lambda: f.eval(wi, wo, out=out), args.repeats))
            assert np.array_equal(f.eval(wi, wo), out)
            per_round = statistics.median(p / c for p, c in zip(py, cpp))
            per_round_out = statistics.median(p / c for p, c in zip(py_out, cpp))
            print(f"{model:<24} {min(cpp):8.2f} {min(py):10.2f} {min(py) / min(cpp):6.3f} {per_round:9.3f} "
                  f"{min(py_out):8.2f} {min(py_out) / min(cpp):6.3f} {per_round_out:9.3f}")


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
