# What the guests' /init scripts share (sourced from /vm/guest_lib.sh): the boot steps
# and the emulated USB devices. busybox sh.

# Busybox's applets, the kernel's file systems, and the modules of /modules/order (one
# a line, with its parameters) in turn. The binaries under test are in /opt/foveal/bin,
# their non-system libraries in /opt/foveal/lib (qemu_guest.py): not at the build
# tree's host path, which the tmpfs on /tmp would hide when the build is under /tmp.
guest_boot() {
  /bin/busybox --install -s /bin
  export PATH=/opt/foveal/bin:/bin:/usr/bin LD_LIBRARY_PATH=/opt/foveal/lib
  mount -t proc proc /proc
  mount -t sysfs sys /sys
  mount -t devtmpfs dev /dev
  mount -t tmpfs tmp /tmp
  echo "VMTEST-BEGIN kernel $(uname -r), uptime $(cut -d' ' -f1 /proc/uptime) s"
  while read -r m params; do
    insmod "/modules/$m" $params || echo "VMTEST modules FAIL insmod $m"
  done < /modules/order
}

# After guest_boot, for the guests that run foveald against gadgets: configfs for the
# gadgets, /dev/shm for the fovea stream (shm_open), foveal's data and a private
# config and runtime directory (the control socket's must not be open to others), /tmp
# as the working directory.
foveald_guest_env() {
  mount -t configfs none /sys/kernel/config
  mkdir -p /dev/shm && mount -t tmpfs shm /dev/shm
  export FOVEAL_DATA_DIR=/foveal XDG_CONFIG_HOME=/tmp/config XDG_RUNTIME_DIR=/tmp/run HOME=/tmp
  mkdir -p "$XDG_CONFIG_HOME" "$XDG_RUNTIME_DIR"
  cd /tmp
}

# wait_until TENTHS COMMAND...: runs COMMAND every 0.1 s until it succeeds, at most
# TENTHS times. Its counter has a name of its own: busybox sh has no locals, and a
# COMMAND that set a plain `n` would end the wait at once.
wait_until() {
  wait_until_left=$1; shift
  until "$@"; do
    wait_until_left=$((wait_until_left - 1)); [ $wait_until_left -le 0 ] && return 1; sleep 0.1
  done
}

# hid_gadget DIR: the USB HID tracker (1209:f0ee) with the real HUTRR74 descriptor
# (/data/tracker.desc) in configfs, not plugged in yet (echo dummy_udc.0 > DIR/UDC).
hid_gadget() {
  mkdir -p $1/strings/0x409 $1/functions/hid.usb0 $1/configs/c.1
  echo 0x1209 > $1/idVendor
  echo 0xf0ee > $1/idProduct
  echo foveal > $1/strings/0x409/manufacturer
  echo "Emulated HUTRR74 tracker" > $1/strings/0x409/product
  echo VM0001 > $1/strings/0x409/serialnumber
  echo 0 > $1/functions/hid.usb0/protocol
  echo 0 > $1/functions/hid.usb0/subclass
  echo 65 > $1/functions/hid.usb0/report_length
  # Feature SET_REPORTs (the Mode Request) then reach /dev/hidg0 instead of stalling.
  echo 1 > $1/functions/hid.usb0/no_out_endpoint
  cat /data/tracker.desc > $1/functions/hid.usb0/report_desc
  ln -s $1/functions/hid.usb0 $1/configs/c.1/
}

# psvr2_gadget DIR FFS [--pose]: the PS VR2 gaze interface (054c:0cde) as a FunctionFS
# function mounted at FFS, with its device side `foveal_vm_guest psvr2-gadget FFS` running
# (pid in PSVR2, output in /tmp/psvr2.log); with --pose also the head-tracking
# interfaces (SLAM, status with IMU records); not plugged in yet.
psvr2_gadget() {
  mkdir -p $1/strings/0x409 $1/functions/ffs.gaze $1/configs/c.1
  echo 0x054c > $1/idVendor
  echo 0x0cde > $1/idProduct
  echo "Emulated PS VR2 gaze" > $1/strings/0x409/product
  ln -s $1/functions/ffs.gaze $1/configs/c.1/
  mkdir -p $2
  mount -t functionfs gaze $2
  foveal_vm_guest psvr2-gadget $2 $3 > /tmp/psvr2.log 2>&1 &
  PSVR2=$!
  wait_until 50 test -e $2/ep1
}

# vive_gadget DIR FFS: an emulated Vive Pro's sensor device (28de:2300, a HID function
# through FunctionFS: IMU reports, the configuration in feature reports) mounted at FFS,
# with `foveal_vm_guest vive-gadget FFS` running (pid in VIVE, output in /tmp/vive.log);
# not plugged in yet.
vive_gadget() {
  mkdir -p $1/strings/0x409 $1/functions/ffs.vive $1/configs/c.1
  echo 0x28de > $1/idVendor
  echo 0x2300 > $1/idProduct
  echo "Valve" > $1/strings/0x409/manufacturer
  echo "Emulated Vive Pro sensors" > $1/strings/0x409/product
  echo VMVIVE0001 > $1/strings/0x409/serialnumber
  ln -s $1/functions/ffs.vive $1/configs/c.1/
  mkdir -p $2
  mount -t functionfs vive $2
  foveal_vm_guest vive-gadget $2 > /tmp/vive.log 2>&1 &
  VIVE=$!
  wait_until 50 test -e $2/ep1
}

# stop_device PID LOG: ends an emulated device's program and prints what it logged.
stop_device() {
  kill $1; wait $1
  cat $2
}

# The PS VR2 gadget is on the bus (as the host side sees it).
psvr2_present() { grep -qs 0cde /sys/bus/usb/devices/*/idProduct; }
