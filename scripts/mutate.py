#!/usr/bin/python3
"""Mutation pass over the BRDF and environment code (issue 16, section 7; docs/testing.md, "Mutation pass").

Each mutant is one small change to one line of src/shadelab/brdf/*.cpp, src/shadelab/envmap/*/*.cpp or the
BRDF kernels (src/shadelab/kernels/*.sl, which brdf/ calls): an arithmetic operator swapped (+ -, * /), a
comparison loosened or tightened, a numeric constant changed, or one of the named mutants below (the two
injected bugs that once survived the suite). For every mutant the script applies it, rebuilds the tests
of its module (ci preset, build/ci), runs them, and restores the file: a brdf mutant first meets the brdf
tests, then the analysis checks of the models its file serves (analysis_filter), an envmap mutant the
envmap tests, each binary stopping the mutant's run at its first failure. A mutant is killed when a test fails
(or hangs past the timeout), survives when every test passes, and is stillborn (not counted) when it does
not compile. Each mutant holds the CPU lock (/tmp/shadelab-cpu.lock, scripts/test.sh's machine-sharing
convention) only for its own build and run, so other work interleaves.

Usage (from the repository root, after a ci build):
  /usr/bin/python3 scripts/mutate.py [--count N] [--seed S] [--only brdf|envmap] [--list] [--named-only]
                                     [--range FIRST:LAST] [--sites-at COMMIT]
The sites are enumerated deterministically; --count N picks N of them with a fixed seed (default: all);
--range runs a part of that list (1-based, inclusive), so a pass can be split over several sittings;
--sites-at COMMIT draws the list from the files as they were at COMMIT (so a later sitting finishes the same
sample after the sources moved) and applies each mutant to the same line text today (a line that no longer
exists is "gone", not counted).
Run it from a checkout where scripts/setup.sh ran (its npm ci puts the independent KTX2 reader in
tools/containers/node_modules): in a fresh worktree without it, the tests that call that reader fail on the
unmutated code and "kill" every mutant that reaches them.
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
        "skip_files": {"registry.cpp", "params.cpp", "game_shading.sl", "sh9.sl", "display.sl", "game_ambient.sl"},
        "targets": ["shadelab_brdf_tests", "shadelab_analysis_tests"],
        # The module's tests first (1 s); then, for a survivor, the analysis checks of the models the file
        # serves (analysis_filter: the whole analysis binary takes about 400 s on one core).
        "binaries": [("src/shadelab/shadelab_brdf_tests", None),
                     ("src/shadelab/shadelab_analysis_tests", "analysis")],
    },
    "envmap": {
        "globs": [("src/shadelab/envmap/base", ".cpp"), ("src/shadelab/envmap/diffuse", ".cpp"),
                  ("src/shadelab/envmap/specular", ".cpp"), ("src/shadelab/kernels", ".sl")],
        "only_files": {"sh9.sl"},  # of the kernels: the SH evaluation envmap uses
        "skip_files": set(),
        "targets": ["shadelab_envmap_tests"],
        "binaries": [("src/shadelab/shadelab_envmap_tests", None)],
    },
}

# The two injected bugs issue 16 reports as survivors, applied by exact text.
NAMED = [
    ("brdf", "src/shadelab/brdf/cook_torrance.cpp", "sample_power_cosine(u, m_p.n + 1.0)",
     "sample_power_cosine(u, m_p.n)", "Blinn-Phong sampler draws exponent n instead of n + 1"),
    ("brdf", "src/shadelab/kernels/cook_torrance.sl", None, None, "default Smith G at twice the roughness"),
]

# The operator mutants, each written once: (text, replacement) pairs of one shape per group.
_BINARY = [("+", "-"), ("-", "+"), ("*", "/"), ("/", "*")]   # between two operands
_COMPARE = [("<", "<="), (">", ">=")]                         # tightened or loosened
_COMPARE_EQ = [("<=", "<"), (">=", ">")]
_CONSTANTS = [("2.0", "1.0"), ("1.0", "2.0"), ("0.5", "0.25"), ("4.0", "2.0")]
OPERATORS = (
    [(re.compile(r"(?<=[\w)\]]) " + re.escape(a) + r" (?=[\w(])"), f" {b} ", f"{a} -> {b}") for a, b in _BINARY]
    + [(re.compile(" " + a + r" (?=[\w(])"), f" {b} ", f"{a} -> {b}") for a, b in _COMPARE]
    + [(re.compile(" " + a + " "), f" {b} ", f"{a} -> {b}") for a, b in _COMPARE_EQ]
    + [(re.compile(r"(?<![\w.])" + re.escape(a) + r"(?![\w.])"), b, f"{a} -> {b}") for a, b in _CONSTANTS]
    + [(re.compile(r"\bpi\b(?!\s*\()"), "(2.0 * pi)", "pi -> 2 pi")]
)


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


def source_files(folder, ext, at):
    """(name, text) of the files of folder ending in ext: the working tree's, or those of commit `at`."""
    if at is None:
        d = os.path.join(ROOT, folder)
        for name in sorted(os.listdir(d)):
            if name.endswith(ext):
                with open(os.path.join(d, name)) as f:
                    yield name, f.read()
        return
    names = subprocess.run(["git", "ls-tree", "--name-only", at, folder + "/"], cwd=ROOT, check=True,
                           stdout=subprocess.PIPE).stdout.decode().split("\n")
    for path in sorted(n for n in names if n.endswith(ext)):
        text = subprocess.run(["git", "show", f"{at}:{path}"], cwd=ROOT, check=True, stdout=subprocess.PIPE).stdout
        yield os.path.basename(path), text.decode()


def sites(module, at=None):
    """Every mutant of the module's files, in a fixed order; with `at`, of the files as they were at that
    commit (so a seeded sample drawn then is drawn again: --sites-at)."""
    cfg = MODULES[module]
    found = []
    for folder, ext in cfg["globs"]:
        for name, text in source_files(folder, ext, at):
            if name.endswith("_test.cpp") or name in cfg["skip_files"]:
                continue
            if ext == ".sl" and "only_files" in cfg and name not in cfg["only_files"]:
                continue
            rel = os.path.join(folder, name)
            lines = text.split("\n")
            for i, line in enumerate(lines):
                code = code_part(line)
                if code is None:
                    continue
                for rx, repl, label in OPERATORS:
                    for m in rx.finditer(code):
                        new = line[: m.start()] + repl + line[m.end():]
                        found.append((module, rel, i, line, new, label))
    return found


def locate(rel, index, line):
    """The line's index in today's file: the same text nearest to where it was, or None when it is gone."""
    path = os.path.join(ROOT, rel)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        lines = f.read().split("\n")
    hits = [i for i, l in enumerate(lines) if l == line]
    return min(hits, key=lambda i: abs(i - index)) if hits else None


# Files that serve several models (or none of the registry's) are judged by every model's defaults set.
SHARED = {"microfacet", "fresnel", "fresnel_materials", "common", "layered", "gloss", "game_lobe", "params"}


def analysis_filter(rel):
    """The gtest filter of the analysis checks that judge a mutant of file rel: the Registry/Models sets of the
    model the file implements (its stem is the model's name), the GGX suites for GGX files, the zoo for the
    Phong family; for a shared file the defaults set of every model and the check and albedo suites."""
    stem = os.path.splitext(os.path.basename(rel))[0]
    if stem in SHARED:
        return "Registry/Models.*_defaults:Check.*:Albedo.*"
    if stem.startswith("ggx"):
        return "Registry/Models.*/ggx_*:Ggx*"
    extra = ":Zoo.*:Albedo.*" if stem in ("phong", "blinn_phong") else ""
    return f"Registry/Models.*/{stem}_*" + extra


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
            for b, which in cfg["binaries"]:
                args = [os.path.join(BUILD, b), "--gtest_brief=1"]
                if which == "analysis":
                    args.append("--gtest_filter=" + analysis_filter(rel))
                code, out = run(args, timeout=TIMEOUT)
                if code != 0:
                    failed = re.findall(r"\[  FAILED  \] ([^\s,]+)", out)
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
    ap.add_argument("--range", default="", help="FIRST:LAST, 1-based, of the chosen list: a pass in parts")
    ap.add_argument("--sites-at", default=None, metavar="COMMIT",
                    help="enumerate the sites in the files as they were at COMMIT (the sample of an earlier "
                         "pass); each mutant is applied to the same line text in today's file")
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
            pool += sites(m, a.sites_at)
        if a.count and a.count < len(pool):
            pool = sorted(random.Random(a.seed).sample(pool, a.count), key=lambda s: (s[1], s[2]))
        chosen += pool
    if a.list:
        for module, rel, i, line, new, label in chosen:
            print(f"{rel}:{i + 1}: {label}: {new.strip()}")
        print(f"{len(chosen)} mutants")
        return 0
    first, last = 1, len(chosen)
    if a.range:
        m = re.fullmatch(r"(\d+):(\d+)", a.range)
        if not m or not 1 <= int(m.group(1)) <= int(m.group(2)):
            print(f"--range: expected FIRST:LAST with 1 <= FIRST <= LAST, got '{a.range}'", file=sys.stderr)
            return 2
        first, last = int(m.group(1)), min(int(m.group(2)), len(chosen))
    tally = {"killed": 0, "survived": 0, "stillborn": 0, "gone": 0}
    start = time.time()
    for k, (module, rel, i, line, new, label) in enumerate(chosen):
        if not first <= k + 1 <= last:
            continue
        if a.sites_at is not None:
            now = locate(rel, i, line)
            if now is None:
                tally["gone"] += 1
                print(f"[{k + 1}/{len(chosen)}] gone      {rel}:{i + 1}: {label}: the line is no longer there", flush=True)
                continue
            i = now
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
    print(f"mutation score: {tally['killed']}/{counted} killed ({tally['stillborn']} stillborn, {tally['gone']} gone, "
          "not counted), "
          f"{time.time() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
