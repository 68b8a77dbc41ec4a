#!/usr/bin/env bash
# Every benchmark in one go, one table (bench/run.py says how; rows in bench/rows.json).
#   bench/run.sh [--build build/release] [--only envmap,cmd] [--markdown FILE]
# Build first: cmake --preset release && cmake --build --preset release
set -euo pipefail
exec /usr/bin/python3 "$(dirname "$0")/run.py" "$@"
