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
import shlex
import shutil
import socket
import struct
import subprocess
import sys
import time
import zlib

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from qemu_guest import BOCHS_MODULE_PARAMS, BOCHS_MODULES, HERE, Initramfs, host_ready, qemu_command, run_console, verdicts

# The standard VGA with an EDID that offers 2880x1600 at the Vive Pro Eye's 90 Hz.
# bochs accepts a mode when two framebuffers of it fit in VRAM (2 x 17.6 MiB).
VGA = "VGA,vgamem_mb=64,edid=on,xres=2880,yres=1600,refresh_rate=90000"


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


def build_initramfs(a, kver, guest_args, guest_out, work):
    img = Initramfs(os.path.join(HERE, "init_drm.sh"))
    img.add_modules(kver, BOCHS_MODULES, BOCHS_MODULE_PARAMS)
    img.add_binaries([a.foveald], img.add_mesa(a.source_dir))
    img.add_tree("/foveal/data/gaze", os.path.join(a.source_dir, "data", "gaze"))
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
    initrd = os.path.join(work, "initrd.cpio")
    cmd = qemu_command(qemu, kver, initrd, 2, 2048, ["-device", VGA, "-qmp", f"unix:{sock},server=on,wait=off"])
    start = time.monotonic()
    ready = {"s": None, "error": None}

    def on_line(line):
        if not line.startswith("VMTEST-DRM-READY") or ready["s"] is not None:
            return None
        ready["s"] = time.monotonic() - start
        t = time.monotonic()
        try:
            qmp_screendump(sock, screen)
        except (OSError, ValueError, RuntimeError) as e:  # QMP: socket errors, bad JSON, error replies
            ready["error"] = e
            print(f"run_drm_vm_test: screendump failed: {e}")
        print(f"run_drm_vm_test: screendump in {time.monotonic() - t:.1f} s", flush=True)
        return b"go\n"

    try:
        lines, _ = run_console(cmd, a.timeout, os.path.join(work, "console.log"), on_line)
    finally:
        os.remove(initrd)  # 200+ MiB, rebuilt by every run
    ok = ready["s"] is not None and ready["error"] is None and os.path.exists(screen)
    ok = verdicts("run_drm_vm_test", lines, ["drm_not_permitted", "drm_busy", "drm_exit"]) and ok
    return ok and check_summary(lines, a.ready_frames), ready["s"]


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

    start = time.monotonic()
    work = os.path.abspath(a.work)
    found = host_ready("run_drm_vm_test", "drivers/gpu/drm/tiny/bochs", work)
    if isinstance(found, int):
        return found
    qemu, kver = found
    guest_args = shlex.split(a.guest_args)
    host_args = shlex.split(a.host_args)
    guest_out = os.path.join("/tmp", out_dir(guest_args, "foveald-out"))  # foveald runs in /tmp
    host_out = out_dir(host_args, None)
    if host_out is None:
        host_out = os.path.join(work, "host-out")
        host_args += ["--out", host_out]

    try:
        size = build_initramfs(a, kver, guest_args, guest_out, work)
    except (OSError, ValueError, subprocess.CalledProcessError) as e:  # ValueError: two libraries, one name
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
