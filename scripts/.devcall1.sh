set -u
o=$OUT
root=$PWD
scripts/device-bench devices >/dev/null 2>&1
run() { .device/run "$@"; }
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -f "$VK_DRIVER_FILES" ] || unset VK_DRIVER_FILES
cold=(run --scene atrium --path flythrough --res 3840x2160 --frames 8 --repeat 1 --warmup 1 --device 0 --scorer cpu)
echo "== cold start, old (6b0ed37)"; run cbrbench-old "${cold[@]}" --out /tmp/cold-old 2>/dev/null | grep -E "^(variant|full|drr|cbr-|taau)"
echo "== cold start, new"; run cbrbench "${cold[@]}" --out /tmp/cold-new 2>/dev/null | grep -E "^(variant|full|drr|cbr-|taau|cbrbench: meas)"
echo "== default 4K, old and new (device-bench wall)"
scripts/device-bench wall 3840x2160 /tmp/wall 2>&1 | tail -n 30
for e in old new; do d=/tmp/wall/cbrbench-3840x2160-forward; [ $e = old ] && d=/tmp/wall/cbrbench-old-3840x2160-forward; echo "-- $e"; grep -E "^(full|drr|cbr|taau)" $d/summary.csv | cut -d, -f1-12; done
echo "== no warm-up at all, 4K, 30 frames x 5, CPU scorer (a ramp the drift test must see)"
run cbrbench run --scene atrium --path flythrough --res 3840x2160 --frames 30 --repeat 5 --warmup 0 --device 0 --scorer cpu --variants full,cbr-aso,drr --out /tmp/nowarm 2>/dev/null | grep -E "^(variant|full|drr|cbr-|taau|cbrbench: meas)"
python3 scripts/health-table /tmp/cold-new /tmp/nowarm /tmp/wall/cbrbench-3840x2160-forward > $o/health-cold-nowarm-default.txt
mkdir -p $o/files; for d in cold-old cold-new nowarm; do cp /tmp/$d/summary.csv $o/files/$d-summary.csv; done
cp /tmp/cold-new/run.json $o/files/cold-new-run.json; cp /tmp/nowarm/run.json $o/files/nowarm-run.json
cp /tmp/wall/cbrbench-3840x2160-forward/summary.csv $o/files/default-new-summary.csv; cp /tmp/wall/cbrbench-old-3840x2160-forward/summary.csv $o/files/default-old-summary.csv
echo "== 20 quiet 1920x1080 default runs"
for i in $(seq 1 20); do run cbrbench run --scene atrium --path flythrough --device 0 --res 1920x1080 --quiet --out /tmp/q/quiet-$i >/dev/null 2>&1 || echo "quiet-$i failed"; done
python3 scripts/health-table /tmp/q/quiet-* > $o/health-quiet-1080p.txt; tail -1 $o/health-quiet-1080p.txt
python3 - <<'PY' > $o/quiet-maxima.txt
import json,glob
lv=[];sp=[];noise=[]
for f in glob.glob('/tmp/q/*/run.json'):
    h=json.load(open(f))['health']
    for v in h['variants']:
        d=v['drift']; noise.append(d['noise'])
        lv += [abs(r-1) for r in d['repetition_ratios']]
print(f"runs {len(glob.glob('/tmp/q/*/run.json'))}: noise {min(noise)*100:.3f}-{max(noise)*100:.3f}%, largest repetition departure {max(lv)*100:.3f}%")
PY
cat $o/quiet-maxima.txt
