#!/usr/bin/env bash
# Install.DebPackage: `cpack -G DEB` makes a package whose control fields name the program and
# its libraries and whose files, unpacked anywhere, run. Exit 77 (skipped) without dpkg-dev.
# Usage: check_deb.sh CPACK BUILD_DIR WORK_DIR VERSION
set -euo pipefail
cpack=$1 build=$2 work=$3 version=$4
fail() { echo "check_deb: $*" >&2; exit 1; }
for tool in dpkg-deb dpkg-shlibdeps; do
  command -v $tool >/dev/null || { echo "check_deb: $tool not installed (dpkg-dev): skipped"; exit 77; }
done

rm -rf "$work"
mkdir -p "$work"
(cd "$build" && "$cpack" -G DEB -B "$work" >"$work/cpack.log" 2>&1) || { tail -20 "$work/cpack.log"; fail "cpack failed"; }
debs=("$work"/cbrbench_*.deb)
[[ ${#debs[@]} == 1 && -f ${debs[0]} ]] || fail "expected one cbrbench_*.deb in $work"
deb=${debs[0]}
[[ $(dpkg-deb -f "$deb" Package) == cbrbench ]] || fail "Package: $(dpkg-deb -f "$deb" Package)"
[[ $(dpkg-deb -f "$deb" Version) == "$version" ]] || fail "Version: $(dpkg-deb -f "$deb" Version), expected $version"
depends=$(dpkg-deb -f "$deb" Depends)
for lib in libvulkan1 libc6 libstdc++6; do
  [[ $depends == *"$lib"* ]] || fail "Depends lacks $lib: $depends"
done
listing=$(dpkg-deb -c "$deb")
grep -q '\./usr/bin/cbrbench -> \.\./lib/cbrbench/cbrbench$' <<<"$listing" || fail "no /usr/bin/cbrbench link: $listing"

dpkg-deb -x "$deb" "$work/root"
got=$("$work/root/usr/bin/cbrbench" --version) || fail "the unpacked program's --version exited $?"
[[ $got == "cbrbench $version (commit "* ]] || fail "--version printed '$got'"
"$work/root/usr/bin/cbrbench" variants >/dev/null || fail "the unpacked program's variants exited $?"
echo "check_deb: $(basename "$deb"): Depends: $depends"
