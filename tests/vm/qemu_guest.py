"""What the QEMU guest tests share (docs/vm-tests.md): the initramfs written straight
from the host's files (busybox-static, kernel modules in load order, binaries with the
libraries `ldd` names, Mesa), the host checks that make a test skip, the serial console
read line by line, and the guest's "VMTEST name PASS|FAIL" verdicts.

Python 3 standard library only; imported by run_drm_vm_test.py and run_usb_vm_test.py.
"""
import glob
import os
import select
import shutil
import stat
import subprocess
import time

SKIP = 77
MULTIARCH = "/usr/lib/x86_64-linux-gnu"
# What Mesa loads at run time (dlopen), beyond what the binary links: glvnd's EGL vendor
# library and its JSON, GBM, and the gallium driver (kms_swrast for a KMS-only device,
# swrast for surfaceless EGL: the same file, added as a link).
MESA_FILES = [f"{MULTIARCH}/libEGL_mesa.so.0", "/usr/share/glvnd/egl_vendor.d/50_mesa.json",
              f"{MULTIARCH}/libgbm.so.1", f"{MULTIARCH}/libglapi.so.0", f"{MULTIARCH}/dri/kms_swrast_dri.so"]
BUSYBOX = "/bin/busybox"
# The direct-mode guests' display: bochs on QEMU's standard VGA, and what it needs, in
# load order. No fbdev emulation: no fbcon drawing on the console under emulation, no
# framebuffer pinned in VRAM.
BOCHS_MODULES = ["bochs"]
BOCHS_MODULE_PARAMS = {"drm_kms_helper.ko": "fbdev_emulation=0"}
HERE = os.path.dirname(os.path.abspath(__file__))
KERNEL_ARGS = "console=ttyS0 panic=-1 quiet loglevel=3"


# Where the binaries under test and their non-system libraries go in the guest: fixed
# folders, whatever the host's build tree is called (docs/vm-tests.md).
GUEST_BIN = "/opt/foveal/bin"
GUEST_LIB = "/opt/foveal/lib"
# The loader's built-in search folders (Debian's glibc, merged /usr: /lib is usr/lib):
# a library here is found in the guest at its host path without any help.
SYSTEM_LIBRARY_DIRS = ("/usr/lib", MULTIARCH, "/usr/lib64")


def is_system_library(path):
    """True for a library (resolved folder, see ldd) in one of the system's folders."""
    return os.path.dirname(path) in SYSTEM_LIBRARY_DIRS


def ldd(paths):
    """The shared libraries (and the dynamic loader) that `ldd` names for these files."""
    out = subprocess.run(["ldd"] + paths, capture_output=True, text=True, check=True).stdout
    libs = set()
    for line in out.splitlines():
        parts = line.split()
        if "=>" in parts and len(parts) > parts.index("=>") + 1 and parts[parts.index("=>") + 1].startswith("/"):
            libs.add(parts[parts.index("=>") + 1])
        elif parts and parts[0].startswith("/") and not line.endswith(":"):  # not a "file:" heading
            libs.add(parts[0])
    # One copy per library: resolve the directory (merged /usr: /lib is usr/lib), keep
    # the name (the soname link, which is what the loader looks for).
    return {os.path.join(os.path.realpath(os.path.dirname(p)), os.path.basename(p)) for p in libs}


class Initramfs:
    """A newc cpio archive written straight from the host's files."""

    def __init__(self, init):
        """An image with /dev/console, the usual mount points, busybox, `init` as /init
        and what init scripts share as /vm/guest_lib.sh."""
        self.entries = {}  # guest path -> (kind, payload, mode)
        self.add("/dev/console", "char", (5, 1), 0o600)
        for d in ("/proc", "/sys", "/tmp", "/modules"):
            self.add(d, "dir", mode=0o755)
        self.add_file("/bin/busybox", BUSYBOX)
        self.add_file("/init", init)
        self.add_file("/vm/guest_lib.sh", os.path.join(HERE, "guest_lib.sh"))

    def _parents(self, path):
        parent = os.path.dirname(path)
        if parent != "/" and parent not in self.entries:
            self._parents(parent)
            self.entries[parent] = ("dir", None, 0o755)

    def add(self, path, kind, payload=None, mode=0o644):
        self._parents(path)
        self.entries[path] = (kind, payload, mode)

    def add_file(self, path, src):
        self.add(path, "file", src, stat.S_IMODE(os.stat(src).st_mode))

    def add_tree(self, path, src):
        for root, _, files in os.walk(src):
            for name in files:
                self.add_file(os.path.normpath(os.path.join(path, os.path.relpath(root, src), name)),
                              os.path.join(root, name))

    def add_modules(self, kver, modules, params=None):
        """The modules and what they need under /modules, and /modules/order: one line a
        module, in load order, with its parameters (init scripts insmod them in turn)."""
        modprobe = shutil.which("modprobe") or "/usr/sbin/modprobe"  # not on a non-root PATH
        params = params or {}
        order = []
        for m in modules:
            deps = subprocess.run([modprobe, "-S", kver, "--show-depends", m], capture_output=True, text=True,
                                  check=True)
            for line in deps.stdout.splitlines():
                if line.startswith("insmod ") and os.path.basename(line.split()[1]) not in order:
                    ko = line.split()[1]
                    order.append(os.path.basename(ko))
                    self.add_file("/modules/" + os.path.basename(ko), ko)
        self.add("/modules/order", "data", "".join(f"{m} {params.get(m, '')}\n" for m in order).encode())

    def add_binaries(self, binaries, extra_libraries=()):
        """Each binary as GUEST_BIN/NAME and the libraries `ldd` names for them and for
        `extra_libraries`: the system's at their host paths, the others (foveal's own,
        from the build tree) in GUEST_LIB. The guest never sees the build tree's path,
        which may be under /tmp, where the guest mounts a tmpfs (guest_lib.sh puts
        GUEST_BIN on PATH and GUEST_LIB on LD_LIBRARY_PATH)."""
        for b in binaries:
            self.add_file(f"{GUEST_BIN}/{os.path.basename(b)}", b)
        for lib in sorted(ldd(list(binaries) + list(extra_libraries))):
            guest = lib if is_system_library(lib) else f"{GUEST_LIB}/{os.path.basename(lib)}"
            if guest in self.entries and self.entries[guest][1] != lib:
                raise ValueError(f"two libraries named {os.path.basename(lib)}: {self.entries[guest][1]} and {lib}")
            self.add_file(guest, lib)
        # Merged /usr: the paths the binaries name (/lib64/ld-linux-x86-64.so.2) lead to usr/.
        for top in ("/lib", "/lib64"):
            if os.path.islink(top):
                self.add(top, "link", os.readlink(top))

    def add_mesa(self, source_dir):
        """Mesa for EGL on llvmpipe (add before add_binaries, which adds their libraries),
        and foveald's shaders and display models under /foveal (FOVEAL_DATA_DIR)."""
        for path in MESA_FILES:
            if not os.path.exists(path):
                raise FileNotFoundError(f"{path} is missing (apt-get install libegl-mesa0 libgbm1 libgl1-mesa-dri)")
            self.add_file(path, path)
        self.add(f"{MULTIARCH}/dri/swrast_dri.so", "link", "kms_swrast_dri.so")
        self.add_tree("/foveal/shaders", os.path.join(source_dir, "shaders"))
        self.add_tree("/foveal/data/display", os.path.join(source_dir, "data", "display"))
        return [p for p in MESA_FILES if p.endswith(".so") or ".so." in p]

    def write(self, out):
        """Writes the archive; returns the bytes of file data in it."""
        def header(ino, mode, size, name, rdev=(0, 0)):
            name = name.encode() + b"\0"
            fields = [ino, mode, 0, 0, 1, 0, size, 0, 0, rdev[0], rdev[1], len(name), 0]
            h = b"070701" + b"".join(b"%08x" % v for v in fields) + name
            return h + b"\0" * (-len(h) % 4)

        total = 0
        with open(out, "wb") as f:
            for ino, path in enumerate(sorted(self.entries), 1):
                kind, payload, mode = self.entries[path]
                name = path.lstrip("/")
                if kind == "dir":
                    f.write(header(ino, stat.S_IFDIR | mode, 0, name))
                elif kind == "char":
                    f.write(header(ino, stat.S_IFCHR | mode, 0, name, payload))
                elif kind == "file":
                    size = os.path.getsize(payload)
                    f.write(header(ino, stat.S_IFREG | mode, size, name))
                    with open(payload, "rb") as src:
                        shutil.copyfileobj(src, f, 1 << 20)
                    f.write(b"\0" * (-size % 4))
                    total += size
                else:  # "link" (payload: the target) or "data" (payload: the bytes)
                    data = payload.encode() if kind == "link" else payload
                    f.write(header(ino, (stat.S_IFLNK | 0o777) if kind == "link" else (stat.S_IFREG | mode),
                                   len(data), name))
                    f.write(data + b"\0" * (-len(data) % 4))
                    total += len(data)
            f.write(header(0, 0, 0, "TRAILER!!!"))
        return total


def find_kernel(module):
    """The newest /boot kernel whose modules include `module` (a path below
    /lib/modules/KVER/kernel, without the .ko suffix), or None."""
    found = None
    for image in sorted(glob.glob("/boot/vmlinuz-*")):
        kver = image[len("/boot/vmlinuz-"):]
        if glob.glob(f"/lib/modules/{kver}/kernel/{module}.ko*"):
            found = kver
    return found


def host_ready(name, module, work):
    """(qemu, kver) when the guest can run here, with `work` made an empty directory;
    else prints why and returns the exit code: SKIP without qemu or a kernel with
    `module`, 1 without a static busybox (scripts/bootstrap.sh --tests installs busybox-static
    with qemu: not a reason to skip)."""
    qemu = shutil.which("qemu-system-x86_64")
    if not qemu:
        print("SKIPPED: qemu-system-x86_64 is not installed (apt-get install qemu-system-x86; scripts/bootstrap.sh --tests does it)")
        return SKIP
    kver = find_kernel(module)
    if not kver:
        print(f"SKIPPED: no Debian kernel image with the {os.path.basename(module)} module in /boot and /lib/modules "
              "(apt-get install linux-image-amd64)")
        return SKIP
    if not os.access(BUSYBOX, os.X_OK) or subprocess.run(["ldd", BUSYBOX], capture_output=True).returncode == 0:
        print(f"{name}: {BUSYBOX} is missing or not static (apt-get install busybox-static)")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    return qemu, kver


def qemu_command(qemu, kver, initrd, smp, mem_mb, extra=()):
    """Software emulation (no KVM), no display, the serial console on stdio."""
    return [qemu, "-accel", "tcg", "-cpu", "max", "-smp", str(smp), "-m", str(mem_mb), "-nodefaults", "-no-reboot",
            "-display", "none", "-monitor", "none", *extra, "-serial", "stdio",
            "-kernel", f"/boot/vmlinuz-{kver}", "-initrd", initrd, "-append", KERNEL_ARGS]


def run_console(cmd, timeout, log_path, on_line=None, prefix="guest: "):
    """Runs the guest, printing and logging its console line by line. `on_line(line)`
    may return bytes to type on the console. Returns (lines, seconds); the guest is
    killed after `timeout` seconds."""
    start = time.monotonic()
    lines = []
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    pending = b""
    try:
        with open(log_path, "w") as log:
            while True:
                left = timeout - (time.monotonic() - start)
                if left <= 0 or not select.select([proc.stdout], [], [], left)[0]:
                    print(f"the guest ran past {timeout} s: killed")
                    break
                chunk = os.read(proc.stdout.fileno(), 65536)
                if not chunk:
                    break
                pending += chunk
                *complete, pending = pending.split(b"\n")
                for raw in complete:
                    line = raw.decode(errors="replace").replace("\r", "")
                    if not line:
                        continue
                    lines.append(line)
                    log.write(line + "\n")
                    print(prefix + line, flush=True)
                    reply = on_line(line) if on_line else None
                    if reply:
                        proc.stdin.write(reply)
                        proc.stdin.flush()
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
    return lines, time.monotonic() - start


def verdicts(name, lines, checks):
    """True when every check printed "VMTEST <check> PASS", none printed FAIL and the
    guest reached VMTEST-END; prints one line per check."""
    ok = True
    for check in checks:
        passed = any(line.startswith(f"VMTEST {check} PASS") for line in lines)
        print(f"{name}: {check} {'passed' if passed else 'FAILED or missing'}")
        ok = ok and passed
    failed = [line for line in lines if line.startswith("VMTEST ") and " FAIL" in line]
    if failed:
        print(f"{name}: {len(failed)} check(s) failed")
        ok = False
    if not any(line.startswith("VMTEST-END") for line in lines):
        print(f"{name}: the guest did not finish")
        ok = False
    return ok
