#!/usr/bin/env bash
# Boots a QEMU guest (software emulation, no KVM) from Debian 12's stock kernel with an
# initramfs holding busybox-static, the USB/HID modules and the test binaries with their
# shared libraries, and checks the "VMTEST" lines its /init prints on the serial console.
# Exit: 0 all passed, 1 a check failed or went missing, 77 skipped (no qemu or kernel).
set -euo pipefail

while (($#)); do
  case $1 in
    --guest) guest=$2 ;; --foveal) foveal=$2 ;; --descriptor) descriptor=$2 ;;
    --init) init=$2 ;; --work) work=$2 ;; --checks) checks=$2 ;; *) echo "run_vm_tests: unknown option $1" >&2; exit 2 ;;
  esac
  shift 2
done

checks=${checks:-uhid_malformed_descriptors uhid_bad_reports uhid_no_fd_leak gadget_read devices record_replay record_unplug gadget_replug}
skip() { echo "SKIPPED: $*"; exit 77; }
qemu=$(command -v qemu-system-x86_64 || true)
[[ -n $qemu ]] || skip "qemu-system-x86_64 is not installed (apt-get install qemu-system-x86; scripts/bootstrap.sh does it)"
kver=""
for k in /boot/vmlinuz-*; do
  v=${k#/boot/vmlinuz-}
  [[ -f /lib/modules/$v/kernel/drivers/usb/gadget/udc/dummy_hcd.ko ]] && kver=$v
done
[[ -n $kver ]] || skip "no Debian kernel image with modules in /boot and /lib/modules (apt-get install linux-image-amd64)"
busybox=/bin/busybox
# Not a reason to skip: bootstrap.sh installs busybox-static and cpio with qemu.
if [[ ! -x $busybox ]] || ldd "$busybox" >/dev/null 2>&1; then
  echo "run_vm_tests: /bin/busybox is missing or not static (apt-get install busybox-static)"; exit 1
fi
command -v cpio >/dev/null || { echo "run_vm_tests: cpio is not installed"; exit 1; }

# kmod's modprobe lives in /usr/sbin, which a non-root PATH may lack.
modprobe=$(command -v modprobe || echo /usr/sbin/modprobe)
[[ -x $modprobe ]] || { echo "run_vm_tests: modprobe (kmod) is not installed"; exit 1; }

start=$(date +%s)
rm -rf "$work" && mkdir -p "$work/root"
root=$work/root
mkdir -p "$root"/{bin,lib/foveal,modules,data,proc,sys,dev,tmp,etc}
cp "$busybox" "$root/bin/busybox"
cp "$init" "$root/init"
cp "$guest" "$foveal" "$root/bin/"
"$guest" hex2bin "$descriptor" "$root/data/tracker.desc"

# Modules in load order (each after what it needs), from the host's view of the kernel.
: > "$root/modules/order"
for m in configfs dummy_hcd libcomposite usb_f_hid usb_f_fs uhid hid usbhid hid_generic; do
  "$modprobe" -S "$kver" --show-depends "$m" | awk '$1 == "insmod" {print $2}'
done | awk '!seen[$0]++' | while read -r ko; do
  cp "$ko" "$root/modules/"
  basename "$ko" >> "$root/modules/order"
done

# Shared libraries at the paths the binaries name, plus the dynamic loader.
for lib in $(ldd "$guest" "$foveal" | awk '/=>/ {print $3} /^\t\/lib/ {print $1}' | sort -u); do
  mkdir -p "$root$(dirname "$lib")"
  cp -L "$lib" "$root$lib"
done

(cd "$root" && find . | cpio -o -H newc --quiet | gzip -1) > "$work/initrd.gz"
echo "run_vm_tests: kernel $kver, initramfs $(du -h "$work/initrd.gz" | cut -f1), built in $(($(date +%s) - start)) s"

log=$work/console.log
set +e
timeout 280 "$qemu" -accel tcg -cpu max -smp 1 -m 512 -nographic -no-reboot -nodefaults -monitor none \
  -serial stdio -kernel "/boot/vmlinuz-$kver" -initrd "$work/initrd.gz" \
  -append "console=ttyS0 panic=-1 quiet loglevel=3" < /dev/null > "$log" 2>&1
qrc=$?
set -e
tr -d '\r' < "$log" | grep -v '^$' || true
echo "run_vm_tests: qemu exit $qrc after $(($(date +%s) - start)) s"

fail=0
for name in $checks; do
  if grep -q "^VMTEST $name PASS" <(tr -d '\r' < "$log"); then
    echo "run_vm_tests: $name passed"
  else
    echo "run_vm_tests: $name FAILED or missing"
    fail=1
  fi
done
if grep -q "^VMTEST .* FAIL" <(tr -d '\r' < "$log"); then fail=1; fi
grep -q "^VMTEST-END" <(tr -d '\r' < "$log") || { echo "run_vm_tests: the guest did not finish"; fail=1; }
exit $fail
