#!/usr/bin/env bash
# Configures (once) and builds cbrbench in Release, incrementally, into build/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${CBR_BUILD_DIR:-$root/build}
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >&2
fi
cmake --build "$build" -j"$(nproc)" >&2
