#!/bin/busybox sh
# /init of the latency guest (built by run_latency_vm_test.py): loads bochs and runs
# foveald in direct mode once per configuration of $CONFIGS ("PACING:LATCH" words) on
# the bundled recording, printing each run's frames.csv and summary.json between
# markers for the host to check and tabulate (docs/latency.md, "The benchmark").
. /vm/guest_lib.sh
guest_boot
wait_until 100 test -e /dev/dri/card0

# CONFIGS, FRAMES, MODE, SIZE, the environment.
. /foveal/vm.conf
mkdir -p "$XDG_CONFIG_HOME" "$XDG_RUNTIME_DIR"
cd /tmp
for config in $CONFIGS; do
  pacing=${config%%:*}
  latch=${config##*:}
  out=/tmp/out-$pacing-$latch
  foveald --drm --mode "$MODE" --size "$SIZE" --scene pattern:checker --no-control --no-shm -q \
    --replay /foveal/data/gaze/vive_pro_eye_TESTNA01.csv --loop --end 10 --frames "$FRAMES" \
    --pacing "$pacing" --latch "$latch" --out "$out" > /tmp/foveald.log 2>&1
  rc=$?
  if [ $rc -eq 0 ] && [ -f "$out/frames.csv" ]; then
    echo "VMTEST run_$pacing-$latch PASS"
  else
    echo "VMTEST run_$pacing-$latch FAIL exit $rc: $(head -c 400 /tmp/foveald.log)"
  fi
  echo "CSV-BEGIN $config"
  cat "$out/frames.csv" 2>/dev/null
  echo "CSV-END"
  echo "SUMMARY-BEGIN $config"
  cat "$out/summary.json" 2>/dev/null
  echo "SUMMARY-END"
done
echo "VMTEST-END"
poweroff -f
