#!/usr/bin/env bash
# Renders SCENE in N shards as a Slurm job array and merges them in a job that depends on it
# (docs/scale-out.md):
#   scripts/render-slurm.sh SCENE N OUT.exr [RENDER OPTION...]
# Prints the two job ids ("array JOBID", "merge JOBID"). The merged OUT is bit for bit
# `shadelab render SCENE --out OUT.exr` with the same options.
# Environment:
#   SHADELAB        the shadelab program, at the same path on every node (default: shadelab on PATH, else
#                   build/ci/tools/shadelab/shadelab)
#   SPLIT           samples (default) or tiles
#   CPUS            CPUs per shard (sbatch --cpus-per-task and shadelab --threads; default 1)
#   SBATCH_ARGS     more sbatch options for both jobs, e.g. "--partition=render --time=2:00:00"
#   PARTS           the parts directory, on a filesystem every node sees (default: OUT's name with .parts)
#   WAIT            1: wait until the merge job has ended and exit with its status
# Resumable: submitting again renders only the parts not yet done (a valid part is skipped). Progress:
# `squeue`, and `shadelab merge --check PARTS/*.exr` (shards present and missing).
set -euo pipefail

if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE N OUT.exr [RENDER OPTION...]" >&2
  exit 2
fi
scene=$1
n=$2
out=$3
shift 3
case "$n" in ''|*[!0-9]*) echo "render-slurm: N '$n' is not a positive integer" >&2; exit 2 ;; esac
# Decimal whatever its leading zeros ("010" is ten, not octal eight), short enough not to wrap (issue 40, 8).
n=${n#"${n%%[!0]*}"}
[ -n "$n" ] || { echo "render-slurm: N must be >= 1" >&2; exit 2; }
[ "${#n}" -le 9 ] || { echo "render-slurm: N '$2' is too large" >&2; exit 2; }
n=$((10#$n))
[ -f "$scene" ] || { echo "render-slurm: '$scene': no such scene file" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "render-slurm: sbatch not found (a Slurm client)" >&2; exit 2; }

here=$(cd "$(dirname "$0")/.." && pwd)
shadelab=${SHADELAB:-$(command -v shadelab || echo "$here/build/ci/tools/shadelab/shadelab")}
[ -x "$shadelab" ] || { echo "render-slurm: '$shadelab' is not an executable shadelab" >&2; exit 2; }
shadelab=$(cd "$(dirname "$shadelab")" && pwd)/$(basename "$shadelab")
split=${SPLIT:-samples}
cpus=${CPUS:-1}
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
out=$(mkdir -p "$(dirname "$out")" && cd "$(dirname "$out")" && pwd)/$(basename "$out")
parts=${PARTS:-${out%.*}.parts}
mkdir -p "$parts/log"
parts=$(cd "$parts" && pwd)

# The arguments shell-quoted and joined by spaces (nothing for none), for sbatch --wrap.
q() {
  local out="" a
  for a in "$@"; do out+="${out:+ }$(printf '%q' "$a")"; done
  printf '%s' "$out"
}
extra=$(q "$@")
# shellcheck disable=SC2086  # SBATCH_ARGS is a list of options
array=$(sbatch --parsable --job-name=shadelab-shards --array="0-$((n - 1))" --cpus-per-task="$cpus" \
  --output="$parts/log/shard-%a.out" ${SBATCH_ARGS:-} \
  --wrap "$(q "$shadelab" render "$scene" --split "$split" --threads "$cpus") --shard \$SLURM_ARRAY_TASK_ID/$n --out $(q "$parts")/part-\$SLURM_ARRAY_TASK_ID.exr $extra")
array=${array%%;*}
wait_args=()
[ "${WAIT:-0}" = 1 ] && wait_args=(--wait)
# The merge lists exactly this run's N parts, so it fails (exit 2, nothing written) if any shard is missing, and
# parts of an earlier run with a larger N (part-K.exr, K >= N) stay out of it.
merge_parts=""
for ((i = 0; i < n; i++)); do merge_parts+=" $(q "$parts/part-$i.exr")"; done
# shellcheck disable=SC2086
rc=0
merge=$(sbatch --parsable --job-name=shadelab-merge --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$parts/log/merge.out" "${wait_args[@]}" ${SBATCH_ARGS:-} \
  --wrap "$(q "$shadelab" merge)$merge_parts --out $(q "$out")") || rc=$?
merge=${merge%%;*}
echo "array ${array}"
echo "merge ${merge}"
if [ "${WAIT:-0}" = 1 ] && [ -n "$merge" ]; then
  # sbatch --wait reports 0 for a job cancelled because its dependency failed: ask for the job's state.
  state=$(scontrol show job -o "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 || true)
  if [ "$state" != COMPLETED ]; then
    echo "render-slurm: the merge job $merge ended ${state:-in an unknown state} (shard logs: $parts/log/)" >&2
    [ "$rc" -ne 0 ] || rc=1
  fi
fi
exit "$rc"
