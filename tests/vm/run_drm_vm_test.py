#!/usr/bin/env python3
"""Direct mode in a QEMU guest: foveald renders through KMS on the emulated standard VGA
(kernel driver bochs) with Mesa's software KMS driver (kms_swrast: llvmpipe on dumb
buffers), QEMU's screendump reads back what is on the screen, and that must match the
same frame rendered headless on the host (PSNR from `foveal metrics`).

Exit: 0 passed, 1 failed, 77 skipped (no qemu, or no kernel with the bochs module).
docs/vm-tests.md describes the flow and its timings.
"""
import argparse
import glob
import json
import os
import select
import shlex
import shutil
import socket
import stat
import struct
import subprocess
import sys
import time
import zlib

SKIP = 77
MULTIARCH = "/usr/lib/x86_64-linux-gnu"
# What Mesa loads at run time (dlopen), beyond what the binary links: glvnd's EGL vendor
# library and its JSON, GBM, and the gallium driver that GBM falls back to on a KMS-only
# device (kms_swrast; swrast_dri.so is the same file).
MESA_FILES = [f"{MULTIARCH}/libEGL_mesa.so.0", "/usr/share/glvnd/egl_vendor.d/50_mesa.json",
              f"{MULTIARCH}/libgbm.so.1", f"{MULTIARCH}/libglapi.so.0", f"{MULTIARCH}/dri/kms_swrast_dri.so"]
# bochs and what it needs, in load order. No fbdev emulation: no fbcon drawing on a
# 2880x1600 console under emulation, no framebuffer pinned in VRAM.
MODULES = ["bochs"]
MODULE_PARAMS = {"drm_kms_helper.ko": "fbdev_emulation=0"}
# The standard VGA with an EDID that offers 2880x1600 at the Vive Pro Eye's 90 Hz.
# bochs accepts a mode when two framebuffers of it fit in VRAM (2 x 17.6 MiB).
VGA = "VGA,vgamem_mb=64,edid=on,xres=2880,yres=1600,refresh_rate=90000"


class Initramfs:
    """A newc cpio archive written straight from the host's files."""

    def __init__(self):
        self.entries = {}  # guest path -> (kind, payload, mode)

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

    def write(self, out):
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


def out_dir(args, default):
    """The --out/-o value of foveald arguments, else the default."""
    for i, a in enumerate(args):
        if a in ("--out", "-o") and i + 1 < len(args):
            return args[i + 1]
        if a.startswith("--out="):
            return a[len("--out="):]
    return default


def read_ppm_rgb(path):
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; no comments in QEMU's
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P6" and fields[3] == b"255", f"{path}: not an 8-bit P6 PPM"
    return int(fields[1]), int(fields[2]), data[pos + 1:]


def write_png_rgb(path, w, h, rgb):
    raw = b"".join(b"\0" + rgb[y * w * 3:(y + 1) * w * 3] for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 1)) + chunk(b"IEND", b""))


def qmp_screendump(sock_path, filename):
    with socket.socket(socket.AF_UNIX) as s:
        s.settimeout(60)
        s.connect(sock_path)
        f = s.makefile("rwb")
        json.loads(f.readline())  # the greeting
        for cmd in ({"execute": "qmp_capabilities"},
                    {"execute": "screendump", "arguments": {"filename": filename}}):
            f.write(json.dumps(cmd).encode() + b"\n")
            f.flush()
            while True:
                reply = json.loads(f.readline())
                if "error" in reply:
                    raise RuntimeError(f"QMP {cmd['execute']}: {reply['error']}")
                if "return" in reply:
                    break  # anything else is an asynchronous event


def find_kernel():
    """The newest /boot kernel whose modules include bochs, or None."""
    found = None
    for image in sorted(glob.glob("/boot/vmlinuz-*")):
        kver = image[len("/boot/vmlinuz-"):]
        if glob.glob(f"/lib/modules/{kver}/kernel/drivers/gpu/drm/tiny/bochs.ko*"):
            found = kver
    return found


def build_initramfs(a, kver, guest_args, guest_out, work):
    img = Initramfs()
    img.add("/dev/console", "char", (5, 1), 0o600)
    for d in ("/proc", "/sys", "/tmp", "/modules"):
        img.add(d, "dir", mode=0o755)
    img.add_file("/bin/busybox", "/bin/busybox")
    img.add_file("/init", os.path.join(os.path.dirname(os.path.abspath(__file__)), "init_drm.sh"))
    img.add_file("/usr/bin/foveald", a.foveald)

    modprobe = shutil.which("modprobe") or "/usr/sbin/modprobe"
    order = []
    for m in MODULES:
        deps = subprocess.run([modprobe, "-S", kver, "--show-depends", m], capture_output=True, text=True, check=True)
        for line in deps.stdout.splitlines():
            if line.startswith("insmod ") and os.path.basename(line.split()[1]) not in order:
                ko = line.split()[1]
                order.append(os.path.basename(ko))
                img.add_file("/modules/" + os.path.basename(ko), ko)
    img.add("/modules/order", "data", "".join(f"{m} {MODULE_PARAMS.get(m, '')}\n" for m in order).encode())

    for path in MESA_FILES:
        if not os.path.exists(path):
            raise FileNotFoundError(f"{path} is missing (apt-get install libegl-mesa0 libgbm1 libgl1-mesa-dri)")
        img.add_file(path, path)
    img.add(f"{MULTIARCH}/dri/swrast_dri.so", "link", "kms_swrast_dri.so")
    for lib in ldd([a.foveald] + [p for p in MESA_FILES if p.endswith(".so") or ".so." in p]):
        img.add_file(lib, lib)
    # Merged /usr: the paths the binaries name (/lib64/ld-linux-x86-64.so.2) lead to usr/.
    for top in ("/lib", "/lib64"):
        if os.path.islink(top):
            img.add(top, "link", os.readlink(top))

    img.add_tree("/foveal/shaders", os.path.join(a.source_dir, "shaders"))
    for sub in ("display", "gaze"):
        img.add_tree(f"/foveal/data/{sub}", os.path.join(a.source_dir, "data", sub))
    for spec in a.extra_file:
        src, _, dst = spec.partition(":")
        img.add_file(dst, src)

    q = shlex.quote
    conf = [f"READY_FRAMES={a.ready_frames}", f"READY_TIMEOUT={a.timeout}", f"GO_TIMEOUT={a.timeout}",
            f"OUT={q(guest_out)}",
            "export FOVEAL_DATA_DIR=/foveal XDG_CONFIG_HOME=/tmp/config XDG_RUNTIME_DIR=/tmp/run HOME=/tmp"]
    conf += [f"export {q(e)}" for e in a.guest_env]
    conf.append("set -- " + " ".join(q(x) for x in guest_args))
    img.add("/foveal/vm.conf", "data", ("\n".join(conf) + "\n").encode())
    return img.write(os.path.join(work, "initrd.cpio"))


def run_guest(a, qemu, kver, work):
    """Boots the guest, takes the screendump when it is ready. Returns (ok, seconds to ready)."""
    sock = os.path.join(work, "qmp.sock")
    screen = os.path.join(work, "screen.ppm")
    cmd = [qemu, "-accel", "tcg", "-cpu", "max", "-smp", "2", "-m", "2048", "-nodefaults", "-no-reboot",
           "-display", "none", "-monitor", "none", "-device", VGA, "-serial", "stdio",
           "-qmp", f"unix:{sock},server=on,wait=off",
           "-kernel", f"/boot/vmlinuz-{kver}", "-initrd", os.path.join(work, "initrd.cpio"),
           "-append", "console=ttyS0 panic=-1 quiet loglevel=3"]
    start = time.monotonic()
    ready_s = None
    lines = []
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    pending = b""
    try:
        with open(os.path.join(work, "console.log"), "w") as log:
            while True:
                left = a.timeout - (time.monotonic() - start)
                if left <= 0 or not select.select([proc.stdout], [], [], left)[0]:
                    print(f"run_drm_vm_test: the guest ran past {a.timeout} s")
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
                    print("guest: " + line, flush=True)
                    if line.startswith("VMTEST-DRM-READY") and ready_s is None:
                        ready_s = time.monotonic() - start
                        t = time.monotonic()
                        qmp_screendump(sock, screen)
                        print(f"run_drm_vm_test: screendump in {time.monotonic() - t:.1f} s", flush=True)
                        proc.stdin.write(b"go\n")
                        proc.stdin.flush()
    except (OSError, ValueError, RuntimeError) as e:  # QMP: socket errors, bad JSON, error replies
        print(f"run_drm_vm_test: screendump failed: {e}")
        ready_s = None
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        os.remove(os.path.join(work, "initrd.cpio"))  # 200+ MiB, rebuilt by every run
    ok = ready_s is not None and os.path.exists(screen)
    for check in ("VMTEST drm_not_permitted PASS", "VMTEST drm_busy PASS", "VMTEST drm_exit PASS", "VMTEST-END"):
        if not any(line.startswith(check) for line in lines):
            print(f"run_drm_vm_test: no '{check}' from the guest")
            ok = False
    if any(line.startswith("VMTEST ") and " FAIL" in line for line in lines):
        ok = False
    return ok and check_summary(lines, a.ready_frames), ready_s


def check_summary(lines, ready_frames):
    """foveald's summary.json from the guest: the output it drove and its frame pacing."""
    try:
        body = lines[lines.index("SUMMARY-BEGIN") + 1:lines.index("SUMMARY-END")]
        out = json.loads("\n".join(body))["render"]["output"]
    except (ValueError, KeyError, TypeError) as e:
        print(f"run_drm_vm_test: no readable summary.json from the guest: {e}")
        return False
    present, mode, connector = out.get("present", {}), out.get("mode", {}), out.get("connector", {})
    checks = {
        "direct mode on the bochs connector": out.get("kind") == "drm" and connector.get("name") == "Virtual-1",
        "the display model's mode, 2880x1600 at 90 Hz": (mode.get("width"), mode.get("height")) == (2880, 1600)
        and abs(mode.get("refresh_hz", 0) - 90) < 0.1,
        "QEMU's EDID read from the connector": (connector.get("edid") or {}).get("vendor") == "RHT",
        f"at least {ready_frames} frames presented": present.get("presented", 0) >= ready_frames,
        # bochs fakes vblank events (sequence 0), so misses are judged by the clock.
        "missed refreshes counted by the clock": present.get("missed_from") == "clock"
        and isinstance(present.get("missed"), int),
    }
    for name, passed in checks.items():
        print(f"run_drm_vm_test: {name}: {'ok' if passed else 'FAILED'}")
    if not all(checks.values()):
        print("run_drm_vm_test: render.output was " + json.dumps(out))
    return all(checks.values())


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--foveald", required=True, help="the binary run in the guest and headless on the host")
    p.add_argument("--foveal", required=True, help="the foveal CLI (its `metrics` computes the PSNR)")
    p.add_argument("--source-dir", required=True, help="the repository root (shaders/, data/)")
    p.add_argument("--work", required=True, help="work directory (initramfs, console.log, images)")
    p.add_argument("--guest-args", required=True, help="foveald's arguments in the guest (one shell-quoted string)")
    p.add_argument("--host-args", required=True,
                   help="foveald's arguments on the host (headless; --out WORK/host-out is added if absent)")
    p.add_argument("--min-psnr", type=float, default=35.0, help="PSNR (dB) the screen must reach (default 35)")
    p.add_argument("--ready-frames", type=int, default=2,
                   help="frames foveald must have presented before the screendump (default 2)")
    p.add_argument("--extra-file", action="append", default=[], metavar="SRC:GUESTPATH",
                   help="a file to put in the guest (repeatable)")
    p.add_argument("--guest-env", action="append", default=[], metavar="NAME=VALUE",
                   help="an environment variable for foveald in the guest (repeatable), e.g. EGL_LOG_LEVEL=debug")
    p.add_argument("--timeout", type=int, default=400, help="seconds the guest may run (default 400)")
    a = p.parse_args()
    for spec in a.extra_file:
        if ":" not in spec:
            p.error(f"--extra-file {spec}: expected SRC:GUESTPATH")

    qemu = shutil.which("qemu-system-x86_64")
    if not qemu:
        print("SKIPPED: qemu-system-x86_64 is not installed (apt-get install qemu-system-x86)")
        return SKIP
    kver = find_kernel()
    if not kver:
        print("SKIPPED: no Debian kernel image with the bochs module in /boot and /lib/modules "
              "(apt-get install linux-image-amd64)")
        return SKIP
    # Not reasons to skip: bootstrap.sh installs busybox-static with qemu.
    if not os.access("/bin/busybox", os.X_OK) or subprocess.run(["ldd", "/bin/busybox"], capture_output=True).returncode == 0:
        print("run_drm_vm_test: /bin/busybox is missing or not static (apt-get install busybox-static)")
        return 1

    start = time.monotonic()
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    guest_args = shlex.split(a.guest_args)
    host_args = shlex.split(a.host_args)
    guest_out = os.path.join("/tmp", out_dir(guest_args, "foveald-out"))  # foveald runs in /tmp
    host_out = out_dir(host_args, None)
    if host_out is None:
        host_out = os.path.join(work, "host-out")
        host_args += ["--out", host_out]

    try:
        size = build_initramfs(a, kver, guest_args, guest_out, work)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"run_drm_vm_test: cannot build the initramfs: {e}")
        return 1
    print(f"run_drm_vm_test: kernel {kver}, initramfs {size / 2**20:.0f} MiB (uncompressed) built in "
          f"{time.monotonic() - start:.1f} s", flush=True)

    t = time.monotonic()
    ok, ready_s = run_guest(a, qemu, kver, work)
    ready = f"ready after {ready_s:.1f} s" if ready_s is not None else "never ready"
    print(f"run_drm_vm_test: guest: {ready} (from qemu's start), ran {time.monotonic() - t:.1f} s", flush=True)
    if not ok:
        print(f"run_drm_vm_test: FAILED in the guest (console: {work}/console.log)")
        return 1

    # The same frames headless on the host, with an empty profile store on both sides.
    t = time.monotonic()
    env = dict(os.environ, FOVEAL_DATA_DIR=os.path.abspath(a.source_dir), XDG_CONFIG_HOME=os.path.join(work, "config"))
    host = subprocess.run([a.foveald] + host_args, env=env, capture_output=True, text=True, timeout=a.timeout)
    print(host.stdout + host.stderr, end="")
    frames = sorted(glob.glob(os.path.join(host_out, "frame_*.png")))
    if host.returncode != 0 or not frames:
        print(f"run_drm_vm_test: the host render failed (exit {host.returncode}, {len(frames)} frames saved)")
        return 1
    print(f"run_drm_vm_test: host render in {time.monotonic() - t:.1f} s -> {frames[-1]}")

    screen = os.path.join(work, "screen.ppm")
    m = subprocess.run([a.foveal, "metrics", "--ref", frames[-1], "--test", screen, "--fovea", "0.5,0.5", "--json"],
                       capture_output=True, text=True)
    psnr = None
    if m.returncode == 0:
        metrics = json.loads(m.stdout)
        psnr = float(metrics["psnr_db"])  # "inf" for identical images
        print(f"run_drm_vm_test: screen vs host frame: PSNR {psnr:.2f} dB (min {a.min_psnr}), "
              f"SSIM {metrics['ssim']:.4f}")
    else:
        print(f"run_drm_vm_test: foveal metrics failed: {m.stdout}{m.stderr}")
    passed = psnr is not None and psnr >= a.min_psnr
    if not passed:
        # Both as PNG, side by side in WORK for an image diff tool.
        shutil.copy(frames[-1], os.path.join(work, "host-frame.png"))
        write_png_rgb(os.path.join(work, "guest-screen.png"), *read_ppm_rgb(screen))
        print(f"run_drm_vm_test: FAILED; see {work}/guest-screen.png and {work}/host-frame.png")
    print(f"run_drm_vm_test: {'passed' if passed else 'failed'} in {time.monotonic() - start:.1f} s")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
