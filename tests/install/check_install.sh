#!/usr/bin/env bash
# Install.PrefixRuns: `cmake --install` into a temporary prefix gives a working cbrbench. The
# installed program prints its version, runs a validated benchmark, and loads its
# OpenImageIO module from the prefix (not from the build tree), also after the prefix moved.
# Usage: check_install.sh CMAKE BUILD_DIR WORK_DIR WITH_OIIO(0|1)
set -euo pipefail
cmake=$1 build=$2 work=$3 with_oiio=$4
fail() { echo "check_install: $*" >&2; exit 1; }

rm -rf "$work"
mkdir -p "$work"
"$cmake" --install "$build" --prefix "$work/prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install failed"; }
exe=$work/prefix/bin/cbrbench
[[ -L $exe && -x $exe ]] || fail "$exe: expected a link to the program"
[[ $(readlink "$exe") != /* ]] || fail "$exe links to an absolute path: $(readlink "$exe")"
[[ -x $work/prefix/lib/cbrbench/cbrbench ]] || fail "lib/cbrbench/cbrbench missing"
if [[ $with_oiio == 1 ]]; then
  [[ -f $work/prefix/lib/cbrbench/libcbr_oiio.so ]] || fail "lib/cbrbench/libcbr_oiio.so missing"
fi

version=$("$exe" --version) || fail "--version exited $?"
[[ $version =~ ^cbrbench\ [0-9]+\.[0-9]+\.[0-9]+\ \(commit\ ([0-9a-f]{7,}|unknown)\)$ ]] ||
  fail "--version printed '$version'; expected 'cbrbench X.Y.Z (commit HASH)'"
[[ $version == "$("$build/harness/cbrbench" --version)" ]] || fail "the installed --version differs from the build's"

out=$work/run
code=0
"$exe" run --res 64x48 --frames 2 --repeat 1 --warmup 0 --variants full,drr --validate --quiet --out "$out" \
  >"$work/run.out" 2>"$work/run.err" || code=$?
[[ $code == 0 ]] || { cat "$work/run.err"; fail "the installed run exited $code"; }
for f in summary.csv frames.csv run.json report.html; do
  [[ -s $out/$f ]] || fail "$out/$f missing or empty"
done
ls "$out"/worst/drr_*.png >/dev/null 2>&1 || fail "$out/worst/ has no drr image"
[[ $(grep -c '^drr,' "$out/summary.csv") == 1 ]] || fail "summary.csv has no drr row"
grep -q 'validation messages: 0 ' "$work/run.out" || fail "validation messages: $(grep validation "$work/run.out")"

# The OpenImageIO module (score reads images through it) comes from the prefix, which may move.
if [[ $with_oiio == 1 ]]; then
  for prefix in "$work/prefix" "$work/moved"; do
    [[ $prefix == "$work/prefix" ]] || mv "$work/prefix" "$prefix"
    imgs=("$out"/worst/drr_*.png)
    LD_DEBUG=files "$prefix/bin/cbrbench" score "${imgs[0]}" "${imgs[0]}" >"$work/score.out" 2>"$work/score.err" ||
      { tail -3 "$work/score.err"; fail "the installed score exited $?"; }
    grep -q "file=$prefix/lib/cbrbench/libcbr_oiio.so .*dynamically loaded" "$work/score.err" ||
      fail "the module was not loaded from $prefix/lib/cbrbench: $(grep 'cbr_oiio.*dynamically' "$work/score.err")"
  done
fi
echo "check_install: $version installed under $work, ran and loaded its files from the prefix"
