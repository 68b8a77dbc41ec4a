#!/usr/bin/env bash
# The README's main command: install dependencies, build (Release) and run shadelab's default job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release
# The CLI, the libraries and the Python module: what the README's later steps (Python, cmake --install) use.
cmake --build --preset release -j "$jobs" --target shadelab_installable
if [ $# -eq 0 ]; then set -- render; fi
./build/release/tools/shadelab/shadelab "$@"
