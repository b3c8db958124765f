#!/usr/bin/env bash
# Installs the Debian 12 packages cbrbench needs, and only those that are missing.
# Sourced by scripts/bench and scripts/test; CBR_WITH_TESTS=1 adds the test-only ones.
set -euo pipefail

cbr_packages=(
  cmake g++ make pkg-config git
  libvulkan-dev mesa-vulkan-drivers glslang-tools
  libglm-dev libtinygltf-dev libstb-dev libdeflate-dev nlohmann-json3-dev libcli11-dev
  libopenimageio-dev libopencv-imgproc-dev
  assimp-testmodels  # the real glTF models the README's and the tutorial's examples load
)
if [[ "${CBR_WITH_TESTS:-0}" == 1 ]]; then
  cbr_packages+=(vulkan-validationlayers libgtest-dev chromium libxml2-utils libbenchmark-tools python3-scipy
    universal-ctags)  # tests/docs/check_lengths.py: where each function ends
  # scripts/sanitize.sh and scripts/fuzz.sh: clang with libFuzzer and the sanitizer runtimes. On Debian 12 those
  # archives are in libclang-rt-14-dev, only recommended by clang-14's libclang-common-14-dev
  # (and recommendations are not installed here), so it is named explicitly.
  cbr_packages+=(clang libclang-rt-dev)
fi

missing=()
for p in "${cbr_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "cbrbench: installing missing Debian packages: ${missing[*]}" >&2
  if [[ $(id -u) -ne 0 ]]; then
    echo "cbrbench: need root to install packages (run as root, or install them yourself)" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
