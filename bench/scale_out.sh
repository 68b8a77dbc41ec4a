#!/usr/bin/env bash
# Speed-up of N local shards (issue 17): one `shadelab render --threads 1` of SCENE against the same render as
# N shards of one thread each under GNU parallel (scripts/render-parallel.sh, merge included), N = the cores
# (default) or $2; paired and alternated, REPEAT times (default 3). Prints each pair and the best ratio
#   efficiency = T(1 process) / (N x T(N shards, wall))          (1.0 = linear)
# and checks the merged bytes equal the single render. Usage: bench/scale_out.sh [SCENE] [N]
# Run it alone on the machine (take the benchmark lock: flock /tmp/shadelab-cpu.lock bench/scale_out.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
scene=${1:-$here/scenes/cornell.json}
n=${2:-$(nproc)}
repeat=${REPEAT:-3}
spp=${SPP:-64}  # long enough that the fixed costs (start, scene load, part write, merge: ~0.5 s) are not the measure
shadelab=${SHADELAB:-$here/build/ci/tools/shadelab/shadelab}
work=$(mktemp -d "${TMPDIR:-/tmp}/shadelab_scale_XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
best=0
for r in $(seq "$repeat"); do
  t0=$(now)
  "$shadelab" render "$scene" --spp "$spp" --threads 1 --no-png --out "$work/one.exr" >/dev/null
  t1=$(now)
  rm -rf "$work/many.parts"
  SHADELAB=$shadelab JOBS=$n THREADS=1 bash "$here/scripts/render-parallel.sh" "$scene" "$n" "$work/many.exr" --spp "$spp" >/dev/null
  t2=$(now)
  cmp -s "$work/one.exr" "$work/many.exr" || { echo "scale_out: merged bytes differ from the single render" >&2; exit 1; }
  eff=$(awk -v a="$t0" -v b="$t1" -v c="$t2" -v n="$n" 'BEGIN { printf "%.3f", (b - a) / (n * (c - b)) }')
  printf 'run %d: 1 process %.2f s, %d shards %.2f s wall (merge included): efficiency %s\n' "$r" \
    "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" "$n" "$(awk -v b="$t1" -v c="$t2" 'BEGIN { print c - b }')" "$eff"
  best=$(awk -v a="$best" -v b="$eff" 'BEGIN { print (b > a) ? b : a }')
done
echo "scale_out: $(basename "$scene") at $spp spp, $n shards on $(nproc) cores: best efficiency $best of linear (target >= 0.90)"
