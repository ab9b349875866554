#!/bin/busybox sh
# /init of the head-tracking guest (run_usb_vm_test.py --mesa, ctest vm_hmd_pose):
# foveald --head psvr2 and then --head vive against the emulated headsets (an emulated
# PS VR2 with its SLAM and status interfaces, an emulated Vive Pro's sensor device),
# the gaze from the synthetic source, rendering headless on llvmpipe. `foveal_vm_guest
# hmd` starts foveald before the headset is plugged in, plugs it in, unplugs it for a
# second, plugs it back, stops foveald and checks what it wrote against the motion the
# headset reported (vm_hmd.cpp): VMTEST hmd_psvr2, hmd_psvr2_replug, hmd_vive,
# hmd_vive_replug, hmd_vive_display_model; before each, the headset read through
# libusb / hidraw directly (vm_hmd_probe.cpp): hmd_psvr2_usb, hmd_vive_hid.
. /vm/guest_lib.sh
guest_boot
foveald_guest_env
# Small frames, ten a second: under emulation the renderer must leave CPU to the devices.
RENDER="--source synthetic --size 64x36 --scene pattern:checker --fps 10 -q"

# probe KIND UDC: the headset plugged in and read through the kernel's interfaces
# directly (hmd_KIND_usb / _hid), then unplugged again for foveald's run.
probe() {
  echo dummy_udc.0 > $2
  foveal_vm_guest hmd-probe $1
  echo "" > $2
  wait_until 600 gadget_gone || echo "hmd_$1: the gadget stayed on the bus after the unplug"
}
# No gadget on the host side's bus any more (only the root hubs, vendor 1d6b).
gadget_gone() { ! grep -qsv 1d6b /sys/bus/usb/devices/*/idVendor; }

P=/sys/kernel/config/usb_gadget/psvr2
psvr2_gadget $P /dev/ffs-gaze --pose
probe psvr2 $P/UDC
foveal_vm_guest hmd psvr2 $P/UDC dummy_udc.0 /tmp/hmd-psvr2 -- foveald --head psvr2 $RENDER
echo "" > $P/UDC
stop_device $PSVR2 /tmp/psvr2.log

V=/sys/kernel/config/usb_gadget/vive
vive_gadget $V /dev/ffs-vive
probe vive $V/UDC
foveal_vm_guest hmd vive $V/UDC dummy_udc.0 /tmp/hmd-vive -- foveald --head vive $RENDER
echo "" > $V/UDC
stop_device $VIVE /tmp/vive.log
echo "VMTEST-END"
poweroff -f
