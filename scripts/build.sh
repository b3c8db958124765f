#!/usr/bin/env bash
# Configures (once) and builds in Release, incrementally, into build/: every target, or
# only those named in CBR_BUILD_TARGETS (scripts/bench builds just cbrbench).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${CBR_BUILD_DIR:-$root/build}
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >&2
fi
targets=()
for t in ${CBR_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}" >&2
