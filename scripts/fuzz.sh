#!/usr/bin/env bash
# Runs every libFuzzer harness (fuzz/README.md) for SECONDS each (default 30) with ASan + UBSan, from the
# committed seed corpus, two at a time (FUZZ_JOBS, default: the number of cores). Usage:
#   bash scripts/fuzz.sh [SECONDS] [HARNESS...]      e.g. bash scripts/fuzz.sh 600 scene cli
# Builds the sanitize preset's fuzz targets first (nothing to do when they are built). A crash, a hang
# (over 10 s on one input), a leak or an allocation over 2 GiB is a finding: the input is saved as
# fuzz/regressions/<harness>/<kind>-<sha1> (the ordinary test suite replays that folder), printed in
# base64 so a CI log carries it, and the script exits with 1 after the other harnesses ran.
# New inputs the fuzzer finds interesting go to build/sanitize/fuzz-corpus/<harness> (not committed).
# FUZZ_SEED (default 1) is libFuzzer's -seed: with the same seed, corpus and code a run takes the same path, so
# a CI finding reproduces and a clean local run of at least CI's length means CI meets nothing new there.
# FUZZ_SEED=0 draws a seed (libFuzzer's default): the way to search beyond that path (docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
shift || true
all=(scene obj gltf glb exr hdr png ktx cli ktx2 shard http scene_dict merl rgl utia)
# Each harness runs SECONDS times its share (default 1): the four of issue 40 (KTX 2 reader, shard parts and
# merge, the served page's request parser, the scene-dict converter) run half as long, so CI's fuzz stage
# grows by about 15 s wall (docs/testing.md, "Fuzz time"); the MERL reader (issue 41) a sixth as long (5 s of
# 30: its input is a header and a size check, or values written into one full-size file), the RGL tensor reader a
# third (10 s: a container of named fields, more paths) and the UTIA reader a sixth (5 s: a size check and values).
declare -A share=([ktx2]=0.5 [shard]=0.5 [http]=0.5 [scene_dict]=0.5 [merl]=0.17 [rgl]=0.33 [utia]=0.17)
harnesses=("$@")
[ ${#harnesses[@]} -eq 0 ] && harnesses=("${all[@]}")
jobs=${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}
seed=${FUZZ_SEED:-1}

[ -f build/sanitize/build.ninja ] || cmake --preset sanitize >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
cmake --build --preset sanitize -j "$jobs" --target "${targets[@]}"

logs=build/sanitize/fuzz-logs
mkdir -p "$logs"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

run_one() {
  local h=$1 seconds=$2 logs=$3 seed=$4
  local corpus=build/sanitize/fuzz-corpus/$h
  mkdir -p "$corpus" "fuzz/regressions/$h"
  local dict=()
  [ -f "fuzz/dict/$h.dict" ] && dict=("-dict=$PWD/fuzz/dict/$h.dict")
  local start=$SECONDS
  if "build/sanitize/fuzz/fuzz_$h" -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=3072 \
      -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 "${dict[@]}" \
      -artifact_prefix="$PWD/fuzz/regressions/$h/" "$PWD/$corpus" "$PWD/fuzz/corpus/$h" "$PWD/fuzz/regressions/$h" \
      >"$logs/$h.log" 2>&1; then
    local execs
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$logs/$h.log" | grep -o '[0-9]*$' || echo "?")
    echo "fuzz $h: ok, $execs runs in $((SECONDS - start)) s (seed $seed), corpus $(ls "$corpus" | wc -l) inputs"
  else
    echo "fuzz $h: FINDING (log: $logs/$h.log)"
    grep -E "ERROR|SUMMARY|finding|runtime error|Test unit written" "$logs/$h.log" | head -20 | sed 's/^/  /'
    for f in fuzz/regressions/"$h"/{crash,timeout,leak,oom,slow-unit}-*; do
      [ -f "$f" ] || continue
      echo "  saved $f ($(stat -c %s "$f") bytes), base64:"
      head -c 65536 "$f" | base64 -w 120 | sed 's/^/    /'
    done
    return 1
  fi
}
export -f run_one

status=0
for h in "${harnesses[@]}"; do
  printf '%s %s\n' "$h" "$(awk -v s="$seconds" -v f="${share[$h]:-1}" 'BEGIN { t = int(s * f + 0.5); print (t < 1 ? 1 : t) }')"
done | xargs -P "$jobs" -L1 bash -c 'run_one "$2" "$3" "$0" "$1"' "$logs" "$seed" || status=1
if [ $status -ne 0 ]; then
  echo "fuzz: findings above; each input is saved under fuzz/regressions/ (commit it with the fix)"
fi
exit $status
