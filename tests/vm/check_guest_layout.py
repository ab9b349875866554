#!/usr/bin/env python3
"""On the host, in a second: the guests' initramfs keeps nothing at the build tree's path
(issue 31: a build under /tmp was hidden by the guest's tmpfs on /tmp). The binaries
are in GUEST_BIN, every library `ldd` names is where the guest's loader looks (a system
folder, or GUEST_LIB, which guest_lib.sh puts on LD_LIBRARY_PATH, with GUEST_BIN on PATH).

Usage: check_guest_layout.py BINARY...   Exit: 0 ok, 1 a problem (each printed).
"""
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from qemu_guest import GUEST_BIN, GUEST_LIB, HERE, Initramfs, is_system_library, ldd


def problems(binaries):
    img = Initramfs(os.path.join(HERE, "init.sh"))
    img.add_binaries(binaries)
    found = []
    trees = {os.path.dirname(os.path.dirname(os.path.realpath(b))) for b in binaries}  # build/bin/X -> build
    for path, (kind, src, _) in sorted(img.entries.items()):
        if kind == "file" and any(path.startswith(t + "/") for t in trees):
            found.append(f"{path} (from {src}) is at the build tree's host path")
    for b in binaries:
        if f"{GUEST_BIN}/{os.path.basename(b)}" not in img.entries:
            found.append(f"{os.path.basename(b)} is not in {GUEST_BIN}")
    for lib in sorted(ldd(binaries)):
        guest = lib if is_system_library(lib) else f"{GUEST_LIB}/{os.path.basename(lib)}"
        if guest not in img.entries:
            found.append(f"{lib} is not in the guest at {guest}")
    with open(os.path.join(HERE, "guest_lib.sh")) as f:
        boot = f.read()
    for var, folder in (("PATH", GUEST_BIN), ("LD_LIBRARY_PATH", GUEST_LIB)):
        if not re.search(rf"\b{var}={re.escape(folder)}\b", boot):
            found.append(f"guest_lib.sh does not put {folder} on {var}")
    return found


def main():
    if len(sys.argv) < 2:
        print(__doc__.strip().split("\n\n")[1])
        return 2
    found = problems([os.path.abspath(b) for b in sys.argv[1:]])
    for p in found:
        print("check_guest_layout: " + p)
    print(f"check_guest_layout: {'FAILED' if found else 'ok'}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
