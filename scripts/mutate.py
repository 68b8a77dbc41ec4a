#!/usr/bin/python3
"""Mutation pass over the BRDF and environment code (issue 16, section 7; docs/testing.md, "Mutation pass").

Each mutant is one small change to one line of src/shadelab/brdf/*.cpp, src/shadelab/envmap/*.cpp or the
BRDF kernels (src/shadelab/kernels/*.sl, which brdf/ calls): an arithmetic operator swapped (+ -, * /), a
comparison loosened or tightened, a numeric constant changed, or one of the named mutants below (the two
injected bugs that once survived the suite). For every mutant the script applies it, rebuilds the tests
of its module (ci preset, build/ci), runs them, and restores the file. A mutant is killed when a test fails
(or hangs past the timeout), survives when every test passes, and is stillborn (not counted) when it does
not compile. Each mutant holds the CPU lock (/tmp/shadelab-cpu.lock, scripts/test.sh's machine-sharing
convention) only for its own build and run, so other work interleaves.

Usage (from the repository root, after a ci build):
  /usr/bin/python3 scripts/mutate.py [--count N] [--seed S] [--only brdf|envmap] [--list] [--named-only]
The sites are enumerated deterministically; --count N picks N of them with a fixed seed (default: all).
Exit code: 0 always after a complete pass (the score is a measurement, not a gate); 2 on bad usage.
"""
import argparse
import fcntl
import os
import random
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, "build", "ci")
LOCK = "/tmp/shadelab-cpu.lock"
TIMEOUT = 300  # seconds for one mutant's tests: a hang is a kill

# Which tests judge a mutant of each module: the module's own tests and the analysis checks (every model's
# normalization, reciprocity, chi-square and weight), plus the render tests' model sweeps for the kernels.
MODULES = {
    "brdf": {
        "globs": [("src/shadelab/brdf", ".cpp"), ("src/shadelab/kernels", ".sl")],
        "skip_files": {"registry.cpp", "params.cpp", "game_shading.sl", "sh9.sl", "sl.h", "kernels.h"},
        "targets": ["shadelab_brdf_tests", "shadelab_analysis_tests"],
        "binaries": ["src/shadelab/shadelab_brdf_tests", "src/shadelab/shadelab_analysis_tests"],
    },
    "envmap": {
        "globs": [("src/shadelab/envmap", ".cpp"), ("src/shadelab/kernels", ".sl")],
        "only_files": {"sh9.sl"},  # of the kernels: the SH evaluation envmap uses
        "skip_files": set(),
        "targets": ["shadelab_envmap_tests"],
        "binaries": ["src/shadelab/shadelab_envmap_tests"],
    },
}

# The two injected bugs issue 16 reports as survivors, applied by exact text.
NAMED = [
    ("brdf", "src/shadelab/brdf/cook_torrance.cpp", "sample_power_cosine(u, m_p.n + 1.0)",
     "sample_power_cosine(u, m_p.n)", "Blinn-Phong sampler draws exponent n instead of n + 1"),
    ("brdf", "src/shadelab/kernels/cook_torrance.sl", None, None, "default Smith G at twice the roughness"),
]

OPERATORS = [
    (re.compile(r"(?<=[\w)\]]) \+ (?=[\w(])"), " - ", "+ -> -"),
    (re.compile(r"(?<=[\w)\]]) - (?=[\w(])"), " + ", "- -> +"),
    (re.compile(r"(?<=[\w)\]]) \* (?=[\w(])"), " / ", "* -> /"),
    (re.compile(r"(?<=[\w)\]]) / (?=[\w(])"), " * ", "/ -> *"),
    (re.compile(r" < (?=[\w(])"), " <= ", "< -> <="),
    (re.compile(r" > (?=[\w(])"), " >= ", "> -> >="),
    (re.compile(r" <= "), " < ", "<= -> <"),
    (re.compile(r" >= "), " > ", ">= -> >"),
    (re.compile(r"(?<![\w.])2\.0(?![\w.])"), "1.0", "2.0 -> 1.0"),
    (re.compile(r"(?<![\w.])1\.0(?![\w.])"), "2.0", "1.0 -> 2.0"),
    (re.compile(r"(?<![\w.])0\.5(?![\w.])"), "0.25", "0.5 -> 0.25"),
    (re.compile(r"(?<![\w.])4\.0(?![\w.])"), "2.0", "4.0 -> 2.0"),
    (re.compile(r"\bpi\b(?!\s*\()"), "(2.0 * pi)", "pi -> 2 pi"),
]


def code_part(line):
    """The line without a // comment, or None for lines that hold no code to mutate."""
    s = line.split("//", 1)[0]
    t = s.strip()
    if not t or t.startswith("#") or t.startswith("*") or t.startswith("/*") or '"' in s:
        return None
    if re.match(r"^(static_assert|namespace|using|template|struct|class|enum|public:|private:)", t):
        return None
    return s


def named_smith_mutant():
    """Finds the Smith G line of the Cook-Torrance kernel and doubles the roughness it is given."""
    path = os.path.join(ROOT, "src/shadelab/kernels/cook_torrance.sl")
    with open(path) as f:
        lines = f.read().split("\n")
    for i, line in enumerate(lines):
        m = re.search(r"G_smith_\w*\(.*?(s\.p\.m)\)", line)
        if m and "//" not in line[: m.start()]:
            new = line[: m.start(1)] + "2.0 * " + line[m.start(1):]
            return i, line, new
    return None


def sites(module):
    cfg = MODULES[module]
    found = []
    for folder, ext in cfg["globs"]:
        d = os.path.join(ROOT, folder)
        for name in sorted(os.listdir(d)):
            if not name.endswith(ext) or name.endswith("_test.cpp") or name in cfg["skip_files"]:
                continue
            if ext == ".sl" and "only_files" in cfg and name not in cfg["only_files"]:
                continue
            if ext == ".sl" and module == "brdf" and name in ("game_shading.sl", "sh9.sl"):
                continue
            rel = os.path.join(folder, name)
            with open(os.path.join(ROOT, rel)) as f:
                lines = f.read().split("\n")
            for i, line in enumerate(lines):
                code = code_part(line)
                if code is None:
                    continue
                for rx, repl, label in OPERATORS:
                    for m in rx.finditer(code):
                        new = line[: m.start()] + repl + line[m.end():]
                        found.append((module, rel, i, line, new, label))
    return found


def run(cmd, timeout=None):
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
        return p.returncode, p.stdout.decode(errors="replace")
    except subprocess.TimeoutExpired:
        return 124, "timeout"


def judge(module, rel, index, new_line):
    """Applies one mutant, builds and runs its module's tests under the CPU lock, restores the file."""
    cfg = MODULES[module]
    path = os.path.join(ROOT, rel)
    with open(path) as f:
        original = f.read()
    lines = original.split("\n")
    lines[index] = new_line
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            with open(path, "w") as f:
                f.write("\n".join(lines))
            code, out = run(["cmake", "--build", BUILD, "-j2", "--target"] + cfg["targets"])
            if code != 0:
                return "stillborn", ""
            for b in cfg["binaries"]:
                code, out = run([os.path.join(BUILD, b), "--gtest_brief=1"], timeout=TIMEOUT)
                if code != 0:
                    failed = re.findall(r"\[  FAILED  \] (\S+)", out)
                    return "killed", (failed[0] if failed else ("timeout" if code == 124 else f"exit {code}"))
            return "survived", ""
        finally:
            with open(path, "w") as f:
                f.write(original)
            os.utime(path, None)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=0)
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--only", choices=sorted(MODULES))
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--named-only", action="store_true")
    a = ap.parse_args()
    modules = [a.only] if a.only else sorted(MODULES)
    chosen = []
    for module, rel, old, new, label in NAMED:
        if module not in modules:
            continue
        path = os.path.join(ROOT, rel)
        if old is None:
            found = named_smith_mutant()
            if found is None:
                print(f"named mutant not found: {label}", file=sys.stderr)
                return 2
            i, line, new_line = found
        else:
            with open(path) as f:
                lines = f.read().split("\n")
            hits = [i for i, l in enumerate(lines) if old in l]
            if len(hits) != 1:
                print(f"named mutant not found once: {label}", file=sys.stderr)
                return 2
            i, line = hits[0], lines[hits[0]]
            new_line = line.replace(old, new)
        chosen.append((module, rel, i, line, new_line, "named: " + label))
    if not a.named_only:
        pool = []
        for m in modules:
            pool += sites(m)
        if a.count and a.count < len(pool):
            pool = sorted(random.Random(a.seed).sample(pool, a.count), key=lambda s: (s[1], s[2]))
        chosen += pool
    if a.list:
        for module, rel, i, line, new, label in chosen:
            print(f"{rel}:{i + 1}: {label}: {new.strip()}")
        print(f"{len(chosen)} mutants")
        return 0
    tally = {"killed": 0, "survived": 0, "stillborn": 0}
    start = time.time()
    for k, (module, rel, i, line, new, label) in enumerate(chosen):
        verdict, by = judge(module, rel, i, new)
        tally[verdict] += 1
        print(f"[{k + 1}/{len(chosen)}] {verdict:9s} {rel}:{i + 1}: {label}: {new.strip()}" + (f"  ({by})" if by else ""),
              flush=True)
    # Rebuild the unmutated tests, so the build folder matches the sources again.
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        targets = sorted({t for m in modules for t in MODULES[m]["targets"]})
        run(["cmake", "--build", BUILD, "-j2", "--target"] + targets)
    counted = tally["killed"] + tally["survived"]
    print(f"mutation score: {tally['killed']}/{counted} killed ({tally['stillborn']} stillborn, not counted), "
          f"{time.time() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
