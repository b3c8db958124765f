#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) into build-fuzz/ and runs each from
# tests/fuzz/corpus/<target> for its share of CBR_FUZZ_SECONDS (default 30). New inputs go
# to a scratch directory, or with --merge into the repository corpus (coverage-minimised).
# Crash inputs land in build-fuzz/artifacts/. Exits non-zero when any target fails.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${CBR_FUZZ_BUILD_DIR:-$root/build-fuzz}
total=${CBR_FUZZ_SECONDS:-30}
merge=0
case "${1:-}" in
  --merge) merge=1 ;;
  "") ;;
  *) echo "usage: scripts/fuzz.sh [--merge]" >&2; exit 2 ;;
esac

# Shares of the time, in percent: the glTF loader has by far the most code to cover; the PNG
# reader is small and fast to run (about 50,000 inputs a second).
targets=(fuzz_gltf fuzz_camera_path fuzz_settings fuzz_png)
shares=(45 25 15 15)

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCBR_FUZZ=ON -DCBR_BUILD_TESTS=OFF -DCBR_WITH_OIIO=OFF >&2
fi
cmake --build "$build" -j"$(nproc)" --target cbr_fuzzers >&2

scratch=$(mktemp -d "${TMPDIR:-/tmp}/cbr-fuzz-corpus.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$build/artifacts"
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}

failed=()
total_execs=0
for i in "${!targets[@]}"; do
  t=${targets[$i]}
  seconds=$(( total * shares[i] / 100 ))
  ((seconds >= 1)) || seconds=1
  corpus=$root/tests/fuzz/corpus/$t
  mkdir -p "$scratch/$t"
  dict=()
  [[ -f "$root/tests/fuzz/$t.dict" ]] && dict=(-dict="$root/tests/fuzz/$t.dict")
  # rss/malloc limits: an input of a few KB that needs a GB is a bug (amplification).
  if ! "$build/tests/fuzz/$t" "${dict[@]}" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 \
        -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix="$build/artifacts/$t-" \
        "$scratch/$t" "$corpus" >"$scratch/$t.log" 2>&1; then
    failed+=("$t")
    tail -n 60 "$scratch/$t.log" >&2
  fi
  execs=$(awk '/stat::number_of_executed_units/ {print $2}' "$scratch/$t.log")
  total_execs=$(( total_execs + ${execs:-0} ))
  echo "fuzz: $t: ${execs:-?} executions in ${seconds} s, $(ls "$scratch/$t" | wc -l) new inputs"
  if ((merge)) && [[ -z "${failed[*]:-}" ]]; then
    "$build/tests/fuzz/$t" -merge=1 "$corpus" "$scratch/$t" >"$scratch/$t.merge.log" 2>&1
  fi
done
echo "fuzz: $total_execs executions in all"
if ((${#failed[@]})); then
  echo "fuzz: FAILED: ${failed[*]} (inputs in $build/artifacts/)" >&2
  exit 1
fi
