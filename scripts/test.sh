#!/usr/bin/env bash
# The README's test command: install what is missing, build, and pass the whole test suite:
#   1. the `ci` preset (Release): unit, validation and slow tests, plus a one-shot smoke run of every benchmark;
#   2. the `asan` preset (AddressSanitizer + UBSan): the unit tests again.
# Set RIFT_SKIP_ASAN=1 to skip step 2 while iterating.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
jobs=$(nproc)
cmake --preset ci
cmake --build --preset ci -j "$jobs"
ctest --preset ci
if [ "${RIFT_SKIP_ASAN:-0}" != "1" ]; then
  cmake --preset asan
  cmake --build --preset asan -j "$jobs"
  ctest --preset asan
fi
