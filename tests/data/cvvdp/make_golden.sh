#!/bin/sh
# Produces golden.json (README.md): runs scripts/cvvdp-golden on every case.
# Run from the repository root:
#   CVVDP_REF=/path/to/patched/ColorVideoVDP PYTHONPATH=/path/to/stubs PYTHON=/usr/bin/python3 \
#     tests/data/cvvdp/make_golden.sh ATRIUM_OUT RAW_DIR
# ATRIUM_OUT: the --out folder of
#   cbrbench run --scene atrium --path flythrough --res 480x270 --frames 30 --save-frames \
#     --variants full,drr,cbr-aso,cbr-cso,cbr-clip,taau --out ATRIUM_OUT
# RAW_DIR: where each case's full cvvdp-golden output goes (not committed).
set -eu
PY=${PYTHON:-python3}
A=$1
RAW=$2
D=tests/data/cvvdp
mkdir -p "$RAW"
g() { name=$1; shift; echo "== $name" >&2; $PY scripts/cvvdp-golden "$@" > "$RAW/$name.json"; }

g image-4k  tests/data/flip/astronaut.png tests/data/flip/astronaut_box2nn.png
g image-fhd tests/data/flip/astronaut.png tests/data/flip/astronaut_box2nn.png --display standard_fhd
for v in drr cbr-aso cbr-cso cbr-clip taau; do
  g atrium-$v "$A/frames/full_[0-9][0-9][0-9][0-9].png" "$A/frames/${v}_[0-9][0-9][0-9][0-9].png" --fps 7.25
done
g flicker-30fps   $D/still.png $D/still.png,$D/still_shift1.png --frames 30 --fps 30
g blur-30fps      $D/still.png $D/still_blur1.5.png --frames 30 --fps 30
g flicker-60fps   $D/still.png $D/still.png,$D/still_shift1.png --frames 12 --fps 60
$PY $D/assemble_golden.py "$RAW" "$A" > $D/golden.json
