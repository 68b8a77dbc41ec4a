#!/usr/bin/env bash
# Runs the README's command-line block ("## The command line", its first ```sh block) top to bottom, as a
# newcomer would after `bash scripts/run.sh`, in a scratch folder that links the repository's scenes/, scripts/
# and the build, so the outputs land there and not in the clone. Stops at the first command that fails and
# says which (exit 1). Each command is echoed with the seconds since the start.
#   BUILD   the build folder whose tools/shadelab/shadelab the block runs (default build/release, as after
#           scripts/run.sh; build/ci works too: it is linked as build/release in the scratch folder)
#   KEEP=1  keep the scratch folder (its path is printed)
# Cost and what it needs: docs/testing.md, "The README's commands in order".
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-build/release}
case "$build" in /*) ;; *) build=$root/$build ;; esac
[ -x "$build/tools/shadelab/shadelab" ] || { echo "readme_commands: no $build/tools/shadelab/shadelab (run bash scripts/run.sh first)" >&2; exit 2; }

block=$(awk '/^## The command line/ { on = 1 } on && /^```sh$/ { inside = 1; next } inside && /^```$/ { exit } inside { print }' "$root/README.md")
[ -n "$block" ] || { echo "readme_commands: no sh block under '## The command line' in README.md" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/shadelab-readme.XXXXXX")
if [ "${KEEP:-0}" = 1 ]; then echo "readme_commands: scratch folder $work"; else trap 'rm -rf "$work"' EXIT; fi
ln -s "$root/scenes" "$work/scenes"
ln -s "$root/scripts" "$work/scripts"
mkdir -p "$work/build"
ln -s "$build" "$work/build/release"
printf '%s\n' "$block" > "$work/readme_block.sh"

cd "$work"
start=$SECONDS
# (PS4 set inside: bash ignores an inherited PS4 when run as root)
if bash -euo pipefail -c 'PS4="+ [\${SECONDS}s] "; set -x; . ./readme_block.sh' > readme_block.log 2>&1; then
  grep '^+ \[' readme_block.log | grep -v '^+ \[[0-9]*s\] \(export\|env=\)' || true
  echo "readme_commands: all $(grep -cv '^\s*$' readme_block.sh) lines ran in $((SECONDS - start)) s"
else
  tail -20 readme_block.log
  echo "readme_commands: FAILED at: $(grep '^+ \[' readme_block.log | tail -1)" >&2
  exit 1
fi
