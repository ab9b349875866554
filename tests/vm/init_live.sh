#!/bin/busybox sh
# /init of the live-daemon guest (run_usb_vm_test.py --mesa): foveald --source hid and
# then --source psvr2 against the emulated devices of the USB/HID suite, rendering
# headless on llvmpipe (surfaceless EGL). `foveal_vm_guest live` starts foveald before
# the device is plugged in, plugs it in, unplugs it for a second, plugs it back, stops
# foveald and checks what it wrote (vm_live.cpp): VMTEST live_hid, live_hid_replug,
# live_psvr2, live_psvr2_replug.
. /vm/guest_lib.sh
guest_boot
foveald_guest_env
# Small frames, ten a second: under emulation the renderer must leave CPU to the gaze side.
# No prediction: each frame must show its trace row's fovea exactly (docs/latency.md).
RENDER="--size 64x36 --scene pattern:checker --fps 10 --predict off -q"

# The HID tracker; its feeder starts once the gadget is plugged in (/dev/hidg0 appears then).
G=/sys/kernel/config/usb_gadget/tracker
hid_gadget $G
(wait_until 1200 test -e /dev/hidg0 && exec foveal_vm_guest feed /dev/hidg0) > /tmp/feed.log 2>&1 &
FEED=$!
foveal_vm_guest live hid $G/UDC dummy_udc.0 /tmp/live-hid -- foveald --source hid $RENDER
stop_device $FEED /tmp/feed.log
echo "" > $G/UDC

# The PS VR2 gaze interface on the same controller.
P=/sys/kernel/config/usb_gadget/psvr2
psvr2_gadget $P /dev/ffs-gaze
foveal_vm_guest live psvr2 $P/UDC dummy_udc.0 /tmp/live-psvr2 -- foveald --source psvr2 $RENDER
stop_device $PSVR2 /tmp/psvr2.log
echo "VMTEST-END"
poweroff -f
