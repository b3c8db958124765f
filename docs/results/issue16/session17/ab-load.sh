#!/bin/bash
# A/B of the PNG decoder inside cbrbench run: alternately stb and fast, N rounds.
scene=$1; n=${2:-7}
json() { grep -o "\"$1\": *[0-9.e+-]*" "$2/run.json" | head -1 | sed -E 's/.*: *//'; }
for i in $(seq $n); do
  for d in stb fast; do
    out=/tmp/ab-$d; rm -rf $out
    CBR_PNG_DECODER=$d /work/main/build/harness/cbrbench run --scene $scene --res 1920x1080 --frames 2 --repeat 1 --warmup 0 --variants full --out $out >/dev/null 2>&1
    f0=$(awk -F, 'NR==1{for(i=1;i<=NF;i++)c[$i]=i;next} $c["frame"]==0{print $c["gpu_ms"]; exit}' $out/frames.csv)
    echo "$d $i load_s $(json load_s $out) upload_s $(json upload_s $out) frame0_ms $f0 first_frame_s $(json first_frame_wall_seconds $out)"
  done
done
