#!/usr/bin/env bash
# The sanitized subset of the ordinary test suite (docs/testing.md, "Sanitizers and fuzzing"): builds the
# GoogleTest binaries below in the sanitize preset (clang-14, ASan + UBSan + float-cast-overflow +
# float-divide-by-zero, -fno-sanitize-recover=all) and runs each with its filter, two at a time
# (SANITIZE_JOBS, default: the number of cores). Any sanitizer report halts its binary with a non-zero exit
# and the script exits with 1 after the others ran. Usage: bash scripts/sanitize_tests.sh [TARGET...]
# (default: the whole subset). scripts/test.sh runs it after the ordinary suite, before the fuzz stage.
set -euo pipefail
cd "$(dirname "$0")/.."

# target:gtest filter. What is left out, and why, is in docs/testing.md.
subset=(
  # the longest first: two at a time, the others share the second slot. Not the eight Blender worlds' irradiance
  # bakes (180 s sanitized, 15 s in Release): the irradiance bake's code runs sanitized in the other bake tests.
  "shadelab_envmap_tests:*-BakeAccuracy.IrradianceBakeWithinOnePercentOnEveryBlenderWorld"
  "shadelab_scene_tests:*"
  # (not the layered ground truth's 1e6-pair sets: its own Layered.FiniteAndNonNegativeEverywhere runs its
  # code paths sanitized, in brdf; its statistical tests, which only add walks, are left out too)
  # (nor openpbr's: its Openpbr.* tests in brdf run its kernel's code paths sanitized; its table lookups make the
  # 1e6 pairs about 16 s unsanitized)
  "shadelab_analysis_tests:Zoo.*:IncompleteGamma.*:ModelsSuite.*:Albedo.*:Registry/Models.FiniteAndNonNegativeEverywhere/*:Registry/Models.Reciprocity/*-*layered*:*openpbr*"
  # 15 s and 8 s of quadrature, no new code path (the openpbr table itself is computed by the other Openpbr* tests)
  "shadelab_kernels_tests:*-Sheen.TableInterpolationErrorBelow1e4:OpenpbrTable.InterpolationErrorAgainstTheConvergedIntegral:OpenpbrTable.QuadratureAgreesWithTheGgxEnergyTable"
  "shadelab_image_tests:*"
  "shadelab_core_tests:*"
  # (not the measured model's arithmetic over whole 35 MB tables, Measured.* and Merl.MeasureEvaluates...: the MERL
  # parser's tests run sanitized; MeasuredRegistry.* does run: the registry route and its cache, on the one MERL file the
  # binary writes, which the every-model tests EvalBatch.* and GameLobe.* also read)
  "shadelab_brdf_tests:*-Measured.*:Merl.MeasureEvaluatesTheModelAtEachBinCentre:Layered.SmoothCoatOverLambertMeetsTheOracle:Layered.TheOracleTellsADifferentBaseApart:Layered.IsReciprocalInExpectation:Layered.ClearCoatOverWhiteLambertIsAWhiteFurnace"
  "shadelab_light_tests:*"
  "shadelab_plot_tests:*"
  # the fitter: NLopt's optimizer driving the models through their whole parameter boxes (not the two spec-gloss
  # conversions: 60 s sanitized, through the same optimizer code as Fit.*)
  "shadelab_fit_tests:*-GltfConvert.*"
)
chosen=()
if [ $# -eq 0 ]; then
  chosen=("${subset[@]}")
else
  for t in "$@"; do
    found=""
    for s in "${subset[@]}"; do [ "${s%%:*}" = "$t" ] && found=$s; done
    [ -n "$found" ] || { echo "sanitize_tests: '$t' is not in the subset (${subset[*]%%:*})" >&2; exit 2; }
    chosen+=("$found")
  done
fi
jobs=${SANITIZE_JOBS:-$(nproc 2>/dev/null || echo 2)}

[ -f build/sanitize/build.ninja ] || cmake --preset sanitize >/dev/null
targets=()
for s in "${chosen[@]}"; do targets+=("${s%%:*}"); done
start=$SECONDS
cmake --build --preset sanitize -j "$jobs" --target "${targets[@]}"
echo "sanitize tests: built in $((SECONDS - start)) s"

logs=build/sanitize/test-logs
mkdir -p "$logs"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Leaks in third-party libraries' process-lifetime caches only (scripts/lsan.supp says which and why).
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"

run_one() {
  local entry=$1 logs=$2
  local target=${entry%%:*} filter=${entry#*:}
  local start=$SECONDS
  if "build/sanitize/src/shadelab/$target" --gtest_brief=1 "--gtest_filter=$filter" >"$logs/$target.log" 2>&1; then
    echo "sanitized $target: ok, $(grep -o '[0-9]* tests\? from' "$logs/$target.log" | head -1 | grep -o '^[0-9]*') tests in $((SECONDS - start)) s"
  else
    echo "sanitized $target: FAILED (log: $logs/$target.log)"
    grep -E "ERROR: |SUMMARY: |runtime error|\[  FAILED  \]" "$logs/$target.log" | head -20 | sed 's/^/  /'
    return 1
  fi
}
export -f run_one

status=0
start=$SECONDS
printf '%s\n' "${chosen[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ {} "$logs" || status=1
echo "sanitize tests: ran in $((SECONDS - start)) s"
exit $status
