#!/bin/busybox sh
# /init of the USB/HID suite's guest (built by run_usb_vm_test.py): loads the USB/HID
# modules, runs the checks, prints "VMTEST ..." lines on the serial console and powers off.
. /vm/guest_lib.sh
guest_boot
mount -t configfs none /sys/kernel/config

# (d) uhid: malformed descriptors and reports.
foveal_vm_guest uhid

# (a) a USB HID gadget with the real HUTRR74 descriptor, on dummy_hcd.
G=/sys/kernel/config/usb_gadget/tracker
hid_gadget $G
echo dummy_udc.0 > $G/UDC
hid_ready() { [ -e /dev/hidg0 ] && ls /dev/hidraw* >/dev/null 2>&1; }
wait_until 100 hid_ready
ls -l /dev/hidg0 /dev/hidraw* 2>&1

foveal_vm_guest feed /dev/hidg0 > /tmp/feed.log 2>&1 &
FEED=$!
foveal_vm_guest probe 1000 60

# foveal devices / foveal record, then the log replayed.
foveal devices --json > /tmp/devices.json 2>&1
cat /tmp/devices.json
if grep -q '"vid_pid": "1209:f0ee"' /tmp/devices.json && grep -q '"sample_rate_hz": 120' /tmp/devices.json; then
  echo "VMTEST devices PASS $(tr -d '\n ' < /tmp/devices.json | head -c 300)"
else
  echo "VMTEST devices FAIL $(tr -d '\n' < /tmp/devices.json | head -c 300)"
fi
foveal record --device auto --out /tmp/rec.csv --duration 4 --json > /tmp/record.json 2>&1
echo "record: rc=$? $(tr -d '\n ' < /tmp/record.json)"
foveal_vm_guest verify-log /tmp/rec.csv 300

# foveal record rides out an unplug: 1 s without the device in a recording. Each step
# waits for its event (the recording has samples, the node is gone, samples come again
# after the replug; the recording's control socket counts them), so a loaded machine only
# makes it slower; the 60 s limits are hang guards.
mkdir -m 700 /tmp/rec2  # the control socket's directory must be closed to others
# From a plugged-in tracker: on a loaded host the emulated bus may still be re-enumerating it.
wait_until 600 hid_ready || echo "record across an unplug: no tracker before the recording"
foveal record --device auto --out /tmp/rec2.csv --duration 600 --control-socket /tmp/rec2/control.sock --json \
  > /tmp/record2.json 2>/tmp/record2.err &
REC=$!
rec_samples() { foveal ctl --socket /tmp/rec2/control.sock --json status 2>/dev/null | grep -o '"samples":[0-9]*' | grep -o '[0-9]*$'; }
rec_has() { have=$(rec_samples); [ "${have:-0}" -ge "$1" ]; }
hidraw_gone() { ! ls /dev/hidraw* >/dev/null 2>&1; }
wait_until 600 rec_has 120 || echo "record across an unplug: no samples before the unplug"
echo "" > $G/UDC
wait_until 600 hidraw_gone || echo "record across an unplug: the node did not go away"
sleep 1; echo dummy_udc.0 > $G/UDC
before=$(rec_samples)
wait_until 600 rec_has $(( ${before:-0} + 150 )) || echo "record across an unplug: no samples after the replug"
kill -INT $REC
wait $REC
echo "record across an unplug: rc=$? $(tr -d '\n ' < /tmp/record2.json)"
if grep -q '"reconnects": 1' /tmp/record2.json; then
  foveal_vm_guest verify-log /tmp/rec2.csv 250 record_unplug
else
  echo "VMTEST record_unplug FAIL no reconnect: $(tr -d '\n' < /tmp/record2.json) $(head -c 200 /tmp/record2.err)"
fi

# (c) 20 unplug/replug cycles, from a plugged-in tracker.
wait_until 600 hid_ready || echo "gadget_replug: the tracker is not back after the recording"
foveal_vm_guest replug $G/UDC dummy_udc.0 20

stop_device $FEED /tmp/feed.log

# (b) an emulated PS VR2 gaze interface through FunctionFS, read by the libusb driver.
echo "" > $G/UDC
P=/sys/kernel/config/usb_gadget/psvr2
psvr2_gadget $P /dev/ffs-gaze
echo dummy_udc.0 > $P/UDC || echo "psvr2: bind failed"
wait_until 50 psvr2_present
ls /dev/bus/usb/*/ 2>&1 | tr '\n' ' '; echo
dmesg | tail -5
foveal_vm_guest psvr2-probe 500 30
foveal devices --json > /tmp/devices2.json 2>&1
if grep -q '"vid_pid": "054c:0cde"' /tmp/devices2.json && grep -q '"driver": "psvr2"' /tmp/devices2.json; then
  echo "VMTEST devices_usb PASS $(tr -d '\n ' < /tmp/devices2.json | head -c 300)"
else
  echo "VMTEST devices_usb FAIL $(tr -d '\n' < /tmp/devices2.json | head -c 300)"
fi
foveal record --device psvr2 --out /tmp/psvr2.csv --duration 2 --json > /tmp/record2.json 2>&1
# The top-level "samples" (the last key; driver_counters has one too).
n=$(grep -o '"samples": [0-9]*' /tmp/record2.json | tail -n 1 | grep -o '[0-9]*$')
if [ "${n:-0}" -ge 100 ] && [ -s /tmp/psvr2.csv ]; then
  echo "VMTEST record_usb PASS samples=$n $(head -c 120 /tmp/psvr2.csv | tr '\n' ' ')"
else
  echo "VMTEST record_usb FAIL $(tr -d '\n' < /tmp/record2.json)"
fi
stop_device $PSVR2 /tmp/psvr2.log
if grep -q "value=030c index=5 data=0c 01" /tmp/psvr2.log; then
  echo "VMTEST psvr2_enable PASS the gadget received the gaze-stream enable request"
else
  echo "VMTEST psvr2_enable FAIL no enable request (report 0x0c, 0x01) reached the gadget"
fi
echo "VMTEST-END"
poweroff -f
