#!/usr/bin/env python3
"""Gaze to photon in direct mode, in a QEMU guest (docs/latency.md): foveald --drm on the
emulated standard VGA (bochs, Mesa's kms_swrast) replays the bundled recording once per
pacing and latch configuration in one boot; the host checks every frame's record and
prints the breakdown of the four configurations side by side.

Checks: every frame with a sample has gaze-to-photon > 0, its four parts add up to it
(within 0.1 ms), and its sample is a row of the replayed log; the shown times are page
flips; each configuration ran with the pacing it names. The host-to-shown time of jit
against asap (median, same latch, same boot) is printed, not checked: it is a speed figure,
and a guest starved by a loaded host misses its vblanks either way (docs/latency.md has
the figures of a quiet machine).

Exit: 0 passed, 1 failed, 77 skipped (no qemu, or no kernel with the bochs module).
"""
import argparse
import csv
import io
import json
import os
import shlex
import statistics
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from qemu_guest import BOCHS_MODULE_PARAMS, BOCHS_MODULES, HERE, Initramfs, host_ready, qemu_command, run_console, verdicts

CONFIGS = ["asap:late", "jit:late", "asap:early", "jit:early"]
PARTS = ["tracker_to_host_ms", "host_to_latch_ms", "latch_to_gpu_ms", "gpu_to_shown_ms"]
LOG = os.path.join("data", "gaze", "vive_pro_eye_TESTNA01.csv")


def log_times(path):
    with open(path) as f:
        rows = [line for line in f if line and not line.startswith("#")]
    return {line.split(",", 1)[0] for line in rows[1:]}


def sections(lines, begin, end):
    """{config: [lines]} between "BEGIN config" and "END" markers."""
    out, current = {}, None
    for line in lines:
        if line.startswith(begin + " "):
            current = line.split(" ", 1)[1]
            out[current] = []
        elif line == end:
            current = None
        elif current is not None:
            out[current].append(line)
    return out


def check_frames(config, rows, times):
    """The frames that have a sample; prints and returns the problems found."""
    problems, framed = [], []
    for r in rows:
        if not r["gaze_to_photon_ms"]:
            continue  # before the first sample
        framed.append(r)
        total = float(r["gaze_to_photon_ms"])
        parts = sum(float(r[p]) for p in PARTS)
        if total <= 0:
            problems.append(f"frame {r['frame']}: gaze-to-photon {total} ms")
        if abs(parts - total) > 0.1:
            problems.append(f"frame {r['frame']}: parts {parts:.3f} ms, total {total:.3f} ms")
        if r["sample_device_t_ns"] not in times:
            problems.append(f"frame {r['frame']}: sample {r['sample_device_t_ns']} is no row of the log")
    if not framed:
        problems.append("no frame with a sample")
    for p in problems[:10]:
        print(f"run_latency_vm_test: {config}: {p}")
    return framed, problems


def pct(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q * (len(s) - 1))))] if s else float("nan")


def host_to_shown(r):
    return float(r["host_to_latch_ms"]) + float(r["latch_to_gpu_ms"]) + float(r["gpu_to_shown_ms"])


def table(results):
    cols = ["gaze_to_photon_ms"] + PARTS
    head = "| pacing:latch | frames | missed | jit margin ms | " + " | ".join(
        c.replace("_ms", "") + " p50 / p95" for c in cols) + " | host→shown p50 |"
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for config, (rows, summary) in results.items():
        pacing = summary.get("render", {}).get("pacing", {})
        margin = pacing.get("margin_ms")
        cells = [f"{pct([float(r[c]) for r in rows], 0.5):.2f} / {pct([float(r[c]) for r in rows], 0.95):.2f}" for c in cols]
        lines.append(f"| {config} | {len(rows)} | {pacing.get('misses', '?')} | "
                     f"{'-' if margin is None else f'{margin:.2f}'} | " + " | ".join(cells) +
                     f" | {statistics.median(host_to_shown(r) for r in rows):.2f} |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--foveald", required=True)
    p.add_argument("--source-dir", required=True, help="the repository root (data/)")
    p.add_argument("--work", required=True, help="work directory (initramfs, console.log)")
    p.add_argument("--frames", type=int, default=120, help="frames per configuration (default 120)")
    p.add_argument("--mode", default="640x360@90", help="the VGA's EDID mode, WxH@HZ (default 640x360@90)")
    p.add_argument("--size", default="320x180", help="foveald's side-by-side size (default 320x180)")
    p.add_argument("--markdown", help="also write the table to this file")
    p.add_argument("--timeout", type=int, default=500)
    a = p.parse_args()
    start = time.monotonic()
    work = os.path.abspath(a.work)
    found = host_ready("run_latency_vm_test", "drivers/gpu/drm/tiny/bochs", work)
    if isinstance(found, int):
        return found
    qemu, kver = found
    w, h_hz = a.mode.split("x", 1)
    h, hz = h_hz.split("@", 1)

    img = Initramfs(os.path.join(HERE, "init_latency.sh"))
    img.add_modules(kver, BOCHS_MODULES, BOCHS_MODULE_PARAMS)
    img.add_binaries([a.foveald], img.add_mesa(a.source_dir))
    img.add_tree("/foveal/data/gaze", os.path.join(a.source_dir, "data", "gaze"))
    q = shlex.quote
    conf = [f"CONFIGS={q(' '.join(CONFIGS))}", f"FRAMES={a.frames}", f"MODE={q(a.mode)}", f"SIZE={q(a.size)}",
            "export FOVEAL_DATA_DIR=/foveal XDG_CONFIG_HOME=/tmp/config XDG_RUNTIME_DIR=/tmp/run HOME=/tmp"]
    img.add("/foveal/vm.conf", "data", ("\n".join(conf) + "\n").encode())
    initrd = img.write(os.path.join(work, "initrd.cpio"))
    vga = f"VGA,vgamem_mb=16,edid=on,xres={w},yres={h},refresh_rate={int(float(hz) * 1000)}"
    cmd = qemu_command(qemu, kver, os.path.join(work, "initrd.cpio"), 2, 1024, ["-device", vga])
    try:
        lines, secs = run_console(cmd, a.timeout, os.path.join(work, "console.log"))
    finally:
        os.remove(os.path.join(work, "initrd.cpio"))
    print(f"run_latency_vm_test: initramfs {initrd / 2**20:.0f} MiB, guest ran {secs:.1f} s")
    ok = verdicts("run_latency_vm_test", lines, [f"run_{c.replace(':', '-')}" for c in CONFIGS])

    times = log_times(os.path.join(a.source_dir, LOG))
    csvs, summaries = sections(lines, "CSV-BEGIN", "CSV-END"), sections(lines, "SUMMARY-BEGIN", "SUMMARY-END")
    results = {}
    for config in CONFIGS:
        rows = list(csv.DictReader(io.StringIO("\n".join(csvs.get(config, [])))))
        try:
            summary = json.loads("\n".join(summaries.get(config, [])))
        except ValueError:
            summary = {}
        framed, problems = check_frames(config, rows, times)
        pacing = summary.get("render", {}).get("pacing", {}).get("pacing")
        if pacing != config.split(":")[0]:
            problems.append(f"paced {pacing!r}, not {config.split(':')[0]}")
            print(f"run_latency_vm_test: {config}: paced {pacing!r}, not {config.split(':')[0]}")
        clock = summary.get("render", {}).get("gaze_to_photon", {}).get("shown_clock")
        if clock != "page_flip":
            problems.append(f"shown clock {clock!r}, not page_flip")
            print(f"run_latency_vm_test: {config}: shown clock {clock!r}, not page_flip")
        ok = ok and not problems
        results[config] = (framed, summary)
    if not ok:
        print(f"run_latency_vm_test: FAILED (console: {work}/console.log)")
        return 1
    text = table(results)
    print(text)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text + "\n")
    for latch in ("late", "early"):
        jit = statistics.median(host_to_shown(r) for r in results[f"jit:{latch}"][0])
        asap = statistics.median(host_to_shown(r) for r in results[f"asap:{latch}"][0])
        print(f"run_latency_vm_test: {latch} latch: host to shown, median, jit {jit:.2f} ms vs asap {asap:.2f} ms "
              f"({'jit shorter' if jit < asap else 'jit not shorter: a loaded host?'})")
    print(f"run_latency_vm_test: {'passed' if ok else 'failed'} in {time.monotonic() - start:.1f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
