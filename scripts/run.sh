#!/usr/bin/env bash
# The README's run command: install what is missing, build Rift (Release, this machine's ISA) and run a
# scene — the built-in default scene when none is given. Extra arguments go to `rift run`.
#   scripts/run.sh                                   # default scene -> rift-out/quickstart/
#   scripts/run.sh scenes/examples/quickstart.yaml --threads 2 --set time.end=2e-4
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
exec build/release/rift run "$@"
