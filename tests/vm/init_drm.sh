#!/bin/busybox sh
# /init of the direct-mode guest (built by run_drm_vm_test.py): loads bochs, starts
# foveald on /dev/dri/card0, prints VMTEST-DRM-READY once it has presented
# $READY_FRAMES frames, waits for the host's "go" on the console (the host takes its
# screendump in between), checks that a second foveald finds the card busy, stops
# foveald with SIGTERM once it has presented one frame more and reports how it exited.
# Before all that: the error an ordinary user gets.
. /vm/guest_lib.sh
guest_boot
wait_until 100 test -e /dev/dri/card0
ls -l /dev/dri 2>&1

# READY_FRAMES, READY_TIMEOUT, GO_TIMEOUT, OUT, the environment, and foveald's
# arguments as "$@".
. /foveal/vm.conf
mkdir -p "$XDG_CONFIG_HOME" "$XDG_RUNTIME_DIR"
cd /tmp

# A second foveald for the error checks: one frame of the same pattern.
SECOND="--drm --scene pattern:checker --no-control --no-shm -q --frames 1 --replay /foveal/constant_gaze.csv"
# Not permitted: devtmpfs leaves the card node 0600 root, so an ordinary user cannot open it.
mkdir -p /etc /tmp/user && chmod 777 /tmp/user
echo "root:x:0:0::/root:/bin/sh" > /etc/passwd
echo "user:x:1000:1000::/tmp/user:/bin/sh" >> /etc/passwd
su -s /bin/sh user -c "XDG_CONFIG_HOME=/tmp/user foveald $SECOND --out /tmp/user/out" > /tmp/perm.log 2>&1
rc=$?
if [ $rc -ne 0 ] && grep -q "not permitted to open /dev/dri/card0" /tmp/perm.log && [ ! -e /tmp/user/out/frames.csv ]; then
  echo "VMTEST drm_not_permitted PASS exit $rc: $(head -c 240 /tmp/perm.log)"
else
  echo "VMTEST drm_not_permitted FAIL exit $rc: $(head -c 400 /tmp/perm.log)"
fi
echo "starting foveald $* at uptime $(cut -d' ' -f1 /proc/uptime) s"
foveald "$@" > /tmp/foveald.log 2>&1 &
PID=$!

# Presented frames: data rows of frames.csv, or of the temporary file it is written
# to until foveald commits it on exit.
rows() {
  for f in "$OUT/frames.csv" "$OUT"/frames.csv.tmp.*; do
    [ -f "$f" ] && { echo $(($(wc -l < "$f") - 1)); return; }
  done
  echo 0
}
# An exited foveald stays a zombie until "wait": kill -0 would still succeed.
running() { [ -e /proc/$PID ] && ! grep -q '^State:[[:space:]]*Z' /proc/$PID/status; }
# At least $1 frames presented, or foveald gone.
presented() { [ "$(rows)" -ge "$1" ] || ! running; }
wait_until $((READY_TIMEOUT * 10)) presented "$READY_FRAMES"
if [ "$(rows)" -ge "$READY_FRAMES" ] && running; then
  echo "VMTEST-DRM-READY $(rows) frames at uptime $(cut -d' ' -f1 /proc/uptime) s"
  read -r -t "$GO_TIMEOUT" go || echo "no go from the host"
  # Busy: the running foveald is the card's DRM master.
  foveald $SECOND --out /tmp/out2 > /tmp/busy.log 2>&1
  rc=$?
  if [ $rc -ne 0 ] && grep -q "/dev/dri/card0 is busy" /tmp/busy.log && [ ! -e /tmp/out2/frames.csv ]; then
    echo "VMTEST drm_busy PASS exit $rc: $(head -c 240 /tmp/busy.log)"
  else
    echo "VMTEST drm_busy FAIL exit $rc: $(head -c 400 /tmp/busy.log)"
  fi
  # SIGTERM abandons the frame in flight (frames take seconds here) and the summary
  # counts the flips completed before it; a frame's flip completes during the next
  # frame's present: one frame more, so that the ready frames' flips are counted.
  wait_until $((READY_TIMEOUT * 10)) presented $((READY_FRAMES + 1))
  kill -TERM $PID
  wait $PID
  rc=$?
  echo "foveald exit $rc at uptime $(cut -d' ' -f1 /proc/uptime) s"
  cat /tmp/foveald.log
  echo "SUMMARY-BEGIN"
  cat "$OUT/summary.json"
  echo "SUMMARY-END"
  cat "$OUT/frames.csv"
  if [ $rc -eq 0 ]; then echo "VMTEST drm_exit PASS"; else echo "VMTEST drm_exit FAIL exit code $rc"; fi
else
  kill -KILL $PID 2>/dev/null
  cat /tmp/foveald.log
  dmesg | tail -n 20
  echo "VMTEST drm_ready FAIL $(rows) of $READY_FRAMES frames presented (foveald exited or ${READY_TIMEOUT} s passed)"
fi
echo "VMTEST-END"
poweroff -f
