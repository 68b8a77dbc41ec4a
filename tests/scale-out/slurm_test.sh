#!/usr/bin/env bash
# issue 17: a real single-node Slurm cluster (munged, slurmctld, slurmd from Debian, started and stopped here by
# scripts/slurm-local.sh), scripts/render-slurm.sh submits the job array and the dependent merge, and the
# merged bytes equal one `shadelab render`.  Usage: slurm_test.sh SHADELAB
# Exit 77 (skipped) only when not root: slurmd must run jobs as their user.
set -euo pipefail
exe=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
scene=$here/scene.json
if [ "$(id -u)" -ne 0 ]; then echo "skipped: a local Slurm cluster needs root"; exit 77; fi
work=$(mktemp -d "${TMPDIR:-/tmp}/shadelab_slurm_XXXXXX")
chmod 0755 "$work"
cleanup() {
  bash "$root/scripts/slurm-local.sh" stop "$work/cluster" || true
  rm -rf "$work"
}
trap cleanup EXIT
bash "$root/scripts/slurm-local.sh" start "$work/cluster"
# shellcheck disable=SC1091
source "$work/cluster/env.sh"

"$exe" render "$scene" --threads 2 --no-png --out "$work/ref.exr" >/dev/null
for case in "samples 4" "tiles 3"; do
  set -- $case
  start=$(date +%s.%N)
  SHADELAB=$exe SPLIT=$1 WAIT=1 bash "$root/scripts/render-slurm.sh" "$scene" "$2" "$work/$1.exr" >"$work/$1.log" || {
    echo "FAIL: the merge job failed"; cat "$work/$1.log" "$work/$1.parts/log/"*.out 2>/dev/null; exit 1; }
  end=$(date +%s.%N)
  grep -q "^array [0-9]" "$work/$1.log" && grep -q "^merge [0-9]" "$work/$1.log" || { echo "FAIL: job ids not printed"; exit 1; }
  cmp "$work/ref.exr" "$work/$1.exr" || { echo "FAIL: $1 split, $2 shards: merged bytes differ from the single render"; exit 1; }
  # Every array task ran as its own Slurm job step and wrote its part.
  [ "$(ls "$work/$1.parts"/part-*.exr | wc -l)" -eq "$2" ] || { echo "FAIL: expected $2 parts"; exit 1; }
  printf 'ok: %s split, %s array tasks + dependent merge on Slurm in %.1f s: merged bytes equal the single render\n' \
    "$1" "$2" "$(awk "BEGIN { print $end - $start }")"
done
# A merge whose array failed does not run (afterok), and no image appears.
if SHADELAB=$exe WAIT=1 bash "$root/scripts/render-slurm.sh" "$scene" 2 "$work/bad.exr" --spp 0 >"$work/bad.log" 2>&1; then
  echo "FAIL: the merge ran although the shards failed"; exit 1
fi
[ ! -e "$work/bad.exr" ] || { echo "FAIL: an image was written"; exit 1; }
echo "ok: failed shards: the dependent merge did not run, no image"
