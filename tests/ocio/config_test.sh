#!/usr/bin/env bash
# share/ocio/shadelab.ocio: OpenColorIO's ociocheck accepts it (exit 0, "passed"), and scripts/make_ocio_config.py
# writes exactly the committed files (the config and its LUTs are the script's output). docs/color.md.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(ociocheck --iconfig "$root/share/ocio/shadelab.ocio" 2>&1)" || { echo "ociocheck failed:"; echo "$out"; exit 1; }
grep -q '^passed' <<<"$out" || { echo "ociocheck did not pass:"; echo "$out"; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 "$root/scripts/make_ocio_config.py" "$tmp"
diff -r "$tmp" "$root/share/ocio" >/dev/null || { echo "share/ocio differs from scripts/make_ocio_config.py's output:"; diff -rq "$tmp" "$root/share/ocio"; exit 1; }
echo "ociocheck passed; share/ocio is make_ocio_config.py's output"
