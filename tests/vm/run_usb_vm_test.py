#!/usr/bin/env python3
"""The USB/HID guests: a QEMU guest (software emulation, no KVM) booted from Debian 12's
stock kernel with the USB gadget modules (dummy_hcd, HID and FunctionFS functions) and
the HID host stack, the test binaries with their shared libraries, the tracker's report
descriptor, and with --mesa foveald's renderer (Mesa, shaders, display models). The
guest's /init (--init) runs the checks; this script reads their "VMTEST name PASS|FAIL"
lines on the serial console.

Exit: 0 all passed, 1 a check failed or went missing, 77 skipped (no qemu or kernel).
docs/vm-tests.md describes the guests and their timings.
"""
import argparse
import os
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from qemu_guest import Initramfs, host_ready, qemu_command, run_console, verdicts

NAME = "run_usb_vm_test"
# The gadget side (configfs, dummy_hcd, HID and FunctionFS functions), the host side
# (uhid, usbhid, hid-generic); what they need comes with them.
MODULES = ["configfs", "dummy_hcd", "libcomposite", "usb_f_hid", "usb_f_fs", "uhid", "hid", "usbhid", "hid_generic"]


def build_initramfs(a, kver, work):
    img = Initramfs(os.path.abspath(a.init))
    img.add_modules(kver, MODULES)
    desc = os.path.join(work, "tracker.desc")
    subprocess.run([a.guest, "hex2bin", a.descriptor, desc], check=True)
    img.add_file("/data/tracker.desc", desc)
    libraries = img.add_mesa(a.source_dir) if a.mesa else []
    img.add_binaries([a.guest] + a.bin, libraries)
    return img.write(os.path.join(work, "initrd.cpio"))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--init", required=True, help="the guest's /init (busybox sh)")
    p.add_argument("--guest", required=True, help="foveal_vm_guest (also converts the descriptor here)")
    p.add_argument("--bin", action="append", default=[], help="another binary for the guest's /opt/foveal/bin (repeatable)")
    p.add_argument("--descriptor", required=True, help="the tracker's report descriptor (hex text)")
    p.add_argument("--mesa", action="store_true", help="add Mesa, shaders/ and data/display/ (needs --source-dir)")
    p.add_argument("--source-dir", help="the repository root (shaders/, data/)")
    p.add_argument("--work", required=True, help="work directory (initramfs, console.log)")
    p.add_argument("--checks", required=True, help="the checks that must pass (space-separated names)")
    p.add_argument("--smp", type=int, default=1, help="guest CPUs (default 1)")
    p.add_argument("--mem", type=int, default=512, help="guest memory in MiB (default 512)")
    p.add_argument("--timeout", type=int, default=280, help="seconds the guest may run (default 280)")
    a = p.parse_args()
    if a.mesa and not a.source_dir:
        p.error("--mesa needs --source-dir")

    start = time.monotonic()
    work = os.path.abspath(a.work)
    found = host_ready(NAME, "drivers/usb/gadget/udc/dummy_hcd", work)
    if isinstance(found, int):
        return found
    qemu, kver = found
    try:
        size = build_initramfs(a, kver, work)
    except (OSError, ValueError, subprocess.CalledProcessError) as e:  # ValueError: two libraries, one name
        print(f"{NAME}: cannot build the initramfs: {e}")
        return 1
    print(f"{NAME}: kernel {kver}, initramfs {size / 2**20:.0f} MiB (uncompressed) built in "
          f"{time.monotonic() - start:.1f} s", flush=True)
    initrd = os.path.join(work, "initrd.cpio")
    try:
        lines, ran = run_console(qemu_command(qemu, kver, initrd, a.smp, a.mem), a.timeout,
                                 os.path.join(work, "console.log"))
    finally:
        os.remove(initrd)  # rebuilt by every run
    print(f"{NAME}: the guest ran {ran:.1f} s")
    ok = verdicts(NAME, lines, a.checks.split())
    print(f"{NAME}: {'passed' if ok else 'FAILED'} in {time.monotonic() - start:.1f} s (console: {work}/console.log)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
