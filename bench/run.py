#!/usr/bin/env python3
"""Runs every benchmark of bench/rows.json in one go and prints one table: each figure, its ceiling,
baseline or peer measured in the same run, and the ratio figure / reference (bench/run.sh is the entry).

    bench/run.sh [--build build/release] [--only envmap,cmd] [--markdown FILE] [--json FILE]

Suites are Google Benchmark programs run once each with --benchmark_format=json (the median of the
repetitions is used where there are repetitions). Commands are timed in CPU seconds of the child process
(user + system, what a shared machine distorts least), alternating the commands of the run ROUNDS times
and keeping the median. A row whose figure or reference was not measured (a program not built, a peer
such as cmft not installed, a benchmark that reported an error) is printed with the reason, never with a
number. With SHADELAB_BENCH_LOCK set to a file, each suite and each command runs under `flock` on it, so
that benchmarks on a shared machine hold the lock in pieces.
"""
import argparse
import json
import os
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
DEFAULT_HDRI = "/usr/share/blender/datafiles/studiolights/world/sunrise.exr"


def locked(argv):
    lock = os.environ.get("SHADELAB_BENCH_LOCK")
    return ["flock", lock] + argv if lock else argv


def expand(text, env):
    out = text
    for key, value in env.items():
        out = out.replace("{" + key + "}", value)
    return out


def run_suite(name, suite, build, scratch):
    binary = build / suite["binary"]
    if not binary.exists():
        return None, f"{binary} is not built"
    out = scratch / f"{name}.json"
    argv = [str(binary), "--benchmark_format=json", f"--benchmark_out={out}"] + suite.get("args", [])
    print(f"[run.sh] {name}: {' '.join(argv[1:])}", file=sys.stderr, flush=True)
    proc = subprocess.run(locked(argv), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if not out.exists():
        return None, f"{binary.name} exited {proc.returncode}: {proc.stderr.strip()[-200:]}"
    try:
        data = json.loads(out.read_text())
    except ValueError:
        return None, f"{binary.name} exited {proc.returncode} without results: {proc.stderr.strip()[-200:]}"
    results = {}
    for b in data.get("benchmarks", []):
        # Google Benchmark appends /real_time, /manual_time, /min_time:X, /iterations:N, /repeats:N: drop them.
        run_name = "/".join(p for p in b.get("run_name", b["name"]).split("/")
                            if p not in ("real_time", "manual_time") and ":" not in p)
        if b.get("error_occurred"):
            results[run_name] = {"error": b.get("error_message", "error")}
            continue
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                results[run_name] = b
        elif run_name not in results or "repetitions" not in b or b.get("repetitions", 1) <= 1:
            results.setdefault(run_name, b)
    return {"context": data.get("context", {}), "results": results}, None


def cpu_seconds(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(locked(["bash", "-c", cmd]), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        return None, f"exit {proc.returncode}: {proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else ''}"
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), None


def run_commands(spec, env, rounds):
    skipped = {}
    active = {}
    for name, c in spec.get("commands", {}).items():
        need = c.get("needs")
        if need and not env.get(need):
            skipped[name] = f"${need} is not set (not installed on this machine)"
            continue
        active[name] = expand(c["cmd"], env)
    times = {name: [] for name in active}
    errors = {}
    for r in range(rounds):
        for name, cmd in active.items():  # alternating: one run of each command per round
            if name in errors:
                continue
            print(f"[run.sh] round {r + 1}/{rounds}: {name}", file=sys.stderr, flush=True)
            t, err = cpu_seconds(cmd)
            if err:
                errors[name] = err
            else:
                times[name].append(t)
    out = {}
    for name in active:
        out[name] = {"error": errors[name]} if name in errors else {"value": statistics.median(times[name])}
    for name, why in skipped.items():
        out[name] = {"error": why}
    return out


def lookup(ref, suites, commands):
    kind, _, rest = ref.partition(":")
    if kind == "const":
        return float(rest), None
    if kind == "cmd":
        r = commands.get(rest)
        if r is None:
            return None, "not run"
        return r.get("value"), r.get("error")
    suite = suites.get(kind)
    if suite is None:
        return None, f"suite {kind} not run"
    if "error" in suite:
        return None, suite["error"]
    bench, _, field = rest.rpartition(":")
    b = suite["results"].get(bench)
    if b is None:
        return None, f"no benchmark {kind}:{bench}"
    if "error" in b:
        return None, b["error"]
    if field not in b:
        return None, f"{kind}:{bench} has no field {field}"
    return float(b[field]), None


def fmt(v):
    if v is None:
        return "-"
    a = abs(v)
    if a >= 1000:
        return f"{v:,.0f}"
    if a >= 10:
        return f"{v:.1f}"
    if a >= 0.1:
        return f"{v:.3f}"
    return f"{v:.3g}"


def meets(ratio, target):
    if ratio is None or not target:
        return ""
    op, _, num = target.partition(" ")
    x = float(num)
    ok = ratio >= x if op == ">=" else ratio <= x
    return "yes" if ok else "NO"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=None, help="build folder (default build/release, else build/ci)")
    ap.add_argument("--only", default="", help="comma-separated suites to run; 'cmd' for the commands")
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds of the commands (median)")
    ap.add_argument("--hdri", default=os.environ.get("SHADELAB_BENCH_HDRI", DEFAULT_HDRI))
    ap.add_argument("--markdown", default=None, help="also write the table (markdown) to this file")
    ap.add_argument("--json", default=None, help="also write every measured value to this file")
    args = ap.parse_args()

    build = Path(args.build) if args.build else next(
        (p for p in (ROOT / "build/release", ROOT / "build/ci") if (p / "tools/shadelab/shadelab").exists()),
        ROOT / "build/release")
    spec = json.loads((HERE / "rows.json").read_text())
    only = {s for s in args.only.split(",") if s}
    scratch = Path(tempfile.mkdtemp(prefix="shadelab-bench-"))
    env = dict(os.environ)
    env.update({"shadelab": str(build / "tools/shadelab/shadelab"), "tmp": str(scratch), "hdri": args.hdri})
    if "CMFT" not in os.environ and shutil.which("cmft"):
        env["CMFT"] = shutil.which("cmft")
    os.environ["SHADELAB_BENCH_HDRI"] = args.hdri
    try:
        suites = {}
        for name, suite in spec["suites"].items():
            if only and name not in only:
                continue
            res, err = run_suite(name, suite, build, scratch)
            suites[name] = res if res else {"error": err}
        commands = {}
        if not only or "cmd" in only:
            for step in spec.get("prepare", []):
                subprocess.run(locked(["bash", "-c", expand(step, env)]), check=True, stdout=subprocess.DEVNULL)
            commands = run_commands(spec, env, args.rounds)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)

    lines = ["| what | figure | reference | reference is | ratio | target | met |", "| --- | ---: | ---: | --- | ---: | --- | --- |"]
    notes = []
    record = []
    for row in spec["rows"]:
        scope = row["figure"].split(":")[0]
        if only and scope not in only:
            continue
        scale = row.get("scale", 1.0)
        f, fe = lookup(row["figure"], suites, commands)
        r, re_ = lookup(row["reference"], suites, commands)
        ratio = f / r if f is not None and r else None
        if row.get("invert") and ratio:
            ratio = 1.0 / ratio
        fs = fmt(f * scale) if f is not None else "not measured"
        rs = fmt(r * scale) if r is not None else "not measured"
        for what, e in ((row["figure"], fe), (row["reference"], re_)):
            if e:
                notes.append(f"- {row['label']}: {what}: {e}")
        lines.append(f"| {row['label']} | {fs} | {rs} | {row['kind']} | {fmt(ratio) if ratio else '-'} | "
                     f"{row.get('target', '')} | {meets(ratio, row.get('target'))} |")
        record.append({"label": row["label"], "figure": f, "reference": r, "ratio": ratio})
    ctx = next((s.get("context") for s in suites.values() if s and "context" in s), {}) or {}
    machine = (f"{ctx.get('host_name', '?')}: {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, "
               f"caches {', '.join(str(c.get('size', '?') // 1024) + ' KiB L' + str(c.get('level')) for c in ctx.get('caches', []))}; "
               f"load {', '.join(f'{x:.2f}' for x in ctx.get('load_avg', []))}; {ctx.get('date', '')}")
    text = "\n".join(lines) + "\n\nMachine: " + machine + "\n" + ("\n" + "\n".join(notes) + "\n" if notes else "")
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(text)
    if args.json:
        Path(args.json).write_text(json.dumps({"machine": machine, "rows": record}, indent=1))


if __name__ == "__main__":
    main()
