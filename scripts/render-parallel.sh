#!/usr/bin/env bash
# Renders SCENE in N shards with GNU parallel and merges them into OUT (docs/scale-out.md):
#   scripts/render-parallel.sh SCENE N OUT.exr [RENDER OPTION...]
# The merged OUT is bit for bit `shadelab render SCENE --out OUT.exr` with the same options.
# Environment:
#   SHADELAB        the shadelab program (default: shadelab on PATH, else build/ci/tools/shadelab/shadelab)
#   SPLIT           samples (default) or tiles
#   JOBS            shards run at once on each host (default: one per core, GNU parallel's --jobs 100%)
#   THREADS         --threads of each shard (default 1 when JOBS is unset, so N local shards fill the cores)
#   PARALLEL_ARGS   more options for GNU parallel, e.g. "-S 4/host1,4/host2 --workdir ." to run over ssh
#                   (every host must see SCENE and the parts directory at the same paths: a shared filesystem)
#   PARTS           the parts directory (default: OUT's name with .parts)
# Resumable: a part already rendered and valid is skipped, so running the same command again finishes what an
# interrupted run left; with another N, the parts are rendered again and the old run's extra parts are left out
# of the merge. N is decimal ("010" is ten). Progress: GNU parallel's --bar on a terminal; `shadelab merge --check PARTS/*.exr`.
set -euo pipefail

if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE N OUT.exr [RENDER OPTION...]" >&2
  exit 2
fi
scene=$1
n=$2
out=$3
shift 3
case "$n" in ''|*[!0-9]*) echo "render-parallel: N '$n' is not a positive integer" >&2; exit 2 ;; esac
# Decimal, whatever its leading zeros ("010" is ten, not octal eight; "08" is eight, not a bash error), and
# short enough that bash's arithmetic cannot wrap; shadelab render --shard bounds it further.
n=${n#"${n%%[!0]*}"}
[ -n "$n" ] || { echo "render-parallel: N must be >= 1" >&2; exit 2; }
[ "${#n}" -le 9 ] || { echo "render-parallel: N '$2' is too large" >&2; exit 2; }
n=$((10#$n))
[ -f "$scene" ] || { echo "render-parallel: '$scene': no such scene file" >&2; exit 2; }
command -v parallel >/dev/null || { echo "render-parallel: GNU parallel not found (Debian package 'parallel')" >&2; exit 2; }

here=$(cd "$(dirname "$0")/.." && pwd)
shadelab=${SHADELAB:-$(command -v shadelab || echo "$here/build/ci/tools/shadelab/shadelab")}
[ -x "$shadelab" ] || { echo "render-parallel: '$shadelab' is not an executable shadelab" >&2; exit 2; }
split=${SPLIT:-samples}
parts=${PARTS:-${out%.*}.parts}
mkdir -p "$parts"

threads_args=()
if [ -n "${THREADS:-}" ]; then threads_args=(--threads "$THREADS"); elif [ -z "${JOBS:-}" ]; then threads_args=(--threads 1); fi
bar=()
[ -t 2 ] && bar=(--bar)
# -q: every argument reaches shadelab as it is (spaces in names included), locally or over ssh.
# shellcheck disable=SC2086  # PARALLEL_ARGS is a list of options
seq 0 $((n - 1)) | parallel --will-cite -q --halt now,fail=1 --jobs "${JOBS:-100%}" "${bar[@]}" ${PARALLEL_ARGS:-} \
  "$shadelab" render "$scene" --shard "{}/$n" --split "$split" --out "$parts/part-{}.exr" "${threads_args[@]}" "$@"
# Exactly the N parts of this run: parts of an earlier run with another N (part-K.exr, K >= N) stay out of the
# merge (they would be foreign parts), and those with K < N were rendered again above (not this very part).
merge_parts=()
for ((i = 0; i < n; i++)); do merge_parts+=("$parts/part-$i.exr"); done
"$shadelab" merge "${merge_parts[@]}" --out "$out"
