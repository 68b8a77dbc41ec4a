#!/usr/bin/env bash
# The README's test command: install dependencies, build (Release, -Werror) and run the whole test suite;
# then the fuzz stage (docs/testing.md, "Sanitizers and fuzzing"): the sanitize preset (clang-14, ASan +
# UBSan with float-cast-overflow and float-divide-by-zero) builds the libFuzzer harnesses and runs each for
# FUZZ_SECONDS (default 30), from the committed seeds and every saved regression input. A sanitizer
# report or a contract break is a finding: saved under fuzz/regressions/, printed, and the run fails.
# Before the fuzzing, the same preset builds and runs the sanitized subset of the ordinary suite
# (scripts/sanitize_tests.sh: which binaries and tests, and what it costs, in docs/testing.md).
# SHADELAB_FUZZ_SECONDS=0 skips the fuzzing; SHADELAB_SANITIZE_TESTS=0 skips the sanitized subset, =1 builds
# the whole suite in the sanitize preset and runs it instead (ctest --preset sanitize; beyond CI's budget).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset ci
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"

fuzz_seconds=${SHADELAB_FUZZ_SECONDS:-30}
sanitize_tests=${SHADELAB_SANITIZE_TESTS:-subset}
if [ "$fuzz_seconds" != 0 ] || [ "$sanitize_tests" != 0 ]; then
  start=$SECONDS
  cmake --preset sanitize
  if [ "$sanitize_tests" = 1 ]; then
    cmake --build --preset sanitize -j "$jobs"
    ctest --preset sanitize -j "$jobs"
  elif [ "$sanitize_tests" != 0 ]; then
    bash scripts/sanitize_tests.sh
  fi
  if [ "$fuzz_seconds" != 0 ]; then
    bash scripts/fuzz.sh "$fuzz_seconds"
  fi
  echo "sanitize stage: $((SECONDS - start)) s"
fi
