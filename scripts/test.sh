#!/usr/bin/env bash
# The README's test command: install dependencies, build (Release, -Werror) and run the whole test suite;
# then the sanitizer stage (docs/testing.md, "Sanitizers and fuzzing"): the sanitize preset (clang-14,
# ASan + UBSan with float-cast-overflow and float-divide-by-zero, -Werror) builds the suite and the fuzz
# harnesses, runs the suite's sanitized subset, and runs each libFuzzer harness for FUZZ_SECONDS (default
# 30). A sanitizer report, a failing test or a fuzz finding (saved under fuzz/regressions/) fails the run.
# SHADELAB_SANITIZE=0 skips the sanitizer stage (a quick local run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset ci
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"

if [ "${SHADELAB_SANITIZE:-1}" != 0 ]; then
  start=$SECONDS
  cmake --preset sanitize
  cmake --build --preset sanitize -j "$jobs"
  echo "sanitize: build $((SECONDS - start)) s"
  t=$SECONDS
  ctest --preset sanitize -j "$jobs"
  echo "sanitize: tests $((SECONDS - t)) s"
  t=$SECONDS
  bash scripts/fuzz.sh "${FUZZ_SECONDS:-30}"
  echo "sanitize: fuzz $((SECONDS - t)) s; the whole stage $((SECONDS - start)) s"
fi
