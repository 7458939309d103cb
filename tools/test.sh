#!/usr/bin/env bash
# The test command of README.md: installs what is missing, builds, runs every unit, CLI, plot
# and QGIS test with CTest (the long-running set is excluded; run it with: ctest -L long).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/tools/build.sh"
cd "$root/build"
ctest --output-on-failure -j"$(nproc)" -LE long
