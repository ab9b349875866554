#!/usr/bin/env python3
"""`foveal bench --shard K/N` and `foveal bench merge` without a cluster: four shards of a
small sweep (and three of a `--gaze` sweep) run one after the other, merged in a shuffled
order, must give the single run's rows, row for row (timing columns left out:
bench_rows.py); bad merges and shard specs exit 2 naming what is wrong and write nothing.

Usage: bench_shard_test.py --foveal BIN. Exit 0 passed, 1 failed.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import bench_rows  # noqa: E402

# Every table the bench writes, with a tiny grid: 2 scenes, 2 levels, a 2×2 f grid,
# rotation, stability, flicker; every method (the default list); and a --gaze sweep on
# two synthetic logs. About 15 s of CPU.
SWEEP = ["--scene", "pattern:noise", "--scene", "pattern:checker", "--sigmas", "2,2.6", "--size", "64x36",
         "--frames", "1", "--warmup", "0", "--f-grid", "--grid-values", "0.2,0.3", "--rotation", "--stability",
         "--flicker", "--flicker-frames", "3"]

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def run(foveal, args):
    return subprocess.run([foveal] + args, capture_output=True, text=True, timeout=300)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--foveal", required=True)
    a = p.parse_args()
    work = tempfile.mkdtemp(prefix="foveal-shard-test-")
    try:
        d = lambda *names: os.path.join(work, *names)  # noqa: E731
        r = run(a.foveal, ["bench"] + SWEEP + ["--no-png", "--out", d("single")])
        check(r.returncode == 0, "the single run: " + r.stderr.strip())
        for k in range(1, 5):
            # Options in another order (the scenes' own order kept): the same sweep.
            r = run(a.foveal, ["bench", "--shard", f"{k}/4", "--out", d(f"shard-{k}")] + SWEEP[4:] + SWEEP[:4])
            check(r.returncode == 0 and os.path.exists(d(f"shard-{k}", "shard.json")), f"shard {k}/4: " + r.stderr.strip())
        points = [json.load(open(d(f"shard-{k}", "shard.json")))["rows"]["points"] for k in range(1, 5)]
        check(len(set(points)) == 1 and points[0] > 4, f"every shard saw the same grid of {points[0]} points")
        # A shard writes its own rows only: between them, all of them once.
        own = sum(len(bench_rows.table(d(f"shard-{k}", "bench.csv"))) - 1 for k in range(1, 5))
        total = len(bench_rows.table(d("single", "bench.csv"))) - 1
        check(own == total, f"the shards' bench.csv rows add up to the single run's {total} ({own})")

        r = run(a.foveal, ["bench", "merge", "--out", d("merged")] + [d(f"shard-{k}") for k in (3, 1, 4, 2)])
        check(r.returncode == 0, "merge: " + r.stderr.strip())
        diffs = bench_rows.differences(d("single"), d("merged"))
        check(not diffs, "the merge equals the single run row for row, all tables and bench.json (timing left out: " +
              ", ".join(bench_rows.timing_columns(d("single", "bench.csv"))) + ")" + "".join("\n      " + x for x in diffs[:10]))
        # The JOD columns (docs/bench.md, "JOD") travel through the shards like the others.
        merged = bench_rows.table(d("merged", "bench.csv"))
        check(merged[0][-3:] == ["jod_left", "jod_right", "jod"] and all(0 < float(x) <= 10 for r in merged[1:] for x in r[-3:]),
              "the merged bench.csv ends with jod_left, jod_right, jod, each in (0, 10]")
        for name in ("flicker.csv", "fgrid.csv", "rotation.csv", "stability.csv"):
            t = bench_rows.table(d("merged", name))
            check(t[0][-3:] == ["jod_left", "jod_right", "jod"] and all(0 < float(x) <= 10 for r in t[1:] for x in r[-3:]),
                  f"the merged {name} ends with jod_left, jod_right, jod, each in (0, 10]")
        for chart in ("pareto.png", "table.md", "fgrid.png", "rotation.png"):
            check(os.path.exists(d("merged", chart)), f"the merge draws {chart} as a single run does")
        # One part of one: a shard too (what an array of one task writes), merged alone.
        r = run(a.foveal, ["bench", "--shard", "1/1", "--out", d("one")] + SWEEP)
        check(r.returncode == 0 and os.path.exists(d("one", "shard.json")), "--shard 1/1 writes a shard " + r.stderr.strip())
        r = run(a.foveal, ["bench", "merge", "--no-png", "--out", d("one-merged"), d("one")])
        check(r.returncode == 0 and not bench_rows.differences(d("single"), d("one-merged")), "a merge of 1/1 equals the single run")

        # A --gaze sweep (scene × log × level, its frames looped over inside): three shards.
        for name, seed in (("g", 3), ("h", 4)):
            r = run(a.foveal, ["synth", "--seed", str(seed), "--duration", "4", "--out", d(name + ".csv")])
            check(r.returncode == 0, f"synth {name}.csv " + r.stderr.strip())
        gaze = ["--gaze", d("g.csv"), "--gaze", d("h.csv"), "--scene", "pattern:noise", "--methods", "rmfr,kfr",
                "--sigmas", "2,3", "--size", "64x36", "--gaze-frames", "3", "--gaze-video", "3", "--frames", "1", "--warmup", "0"]
        r = run(a.foveal, ["bench"] + gaze + ["--no-png", "--out", d("gaze-single")])
        check(r.returncode == 0, "the single --gaze run " + r.stderr.strip())
        for k in range(1, 4):
            r = run(a.foveal, ["bench"] + gaze + ["--shard", f"{k}/3", "--out", d(f"gaze-{k}")])
            check(r.returncode == 0, f"--gaze shard {k}/3 " + r.stderr.strip())
        r = run(a.foveal, ["bench", "merge", "--out", d("gaze-merged")] + [d(f"gaze-{k}") for k in (2, 3, 1)])
        check(r.returncode == 0 and os.path.exists(d("gaze-merged", "gaze.png")), "merge of the --gaze shards, gaze.png " + r.stderr.strip())
        diffs = bench_rows.differences(d("gaze-single"), d("gaze-merged"))
        check(not diffs, "the --gaze merge equals the single run row for row (gaze.csv, gaze_frames.csv, gaze.json; "
              "timing left out)" + "".join("\n      " + x for x in diffs[:10]))
        check(bench_rows.table(d("gaze-merged", "gaze_frames.csv"))[0][-4:] == ["jod_left", "jod_right", "jod", "true_ecc_deg"] and
              bench_rows.table(d("gaze-merged", "gaze.csv"))[0][-3:] == ["jod_mean", "jod_p5", "jod_min"],
              "the merged gaze_frames.csv and gaze.csv end with their JOD columns")
        video = bench_rows.table(d("gaze-merged", "gaze_video.csv"))
        check(len(video) == 1 + 2 * 2 * 3 and video[0][11:15] == ["jod_left", "jod_right", "jod", "temporal"],
              f"the merged gaze_video.csv has a row per log, level and point (oracle, rmfr, kfr): {len(video) - 1}")
        check(len(bench_rows.table(d("gaze-merged", "gaze_video_frames.csv"))) > len(video),
              "the merged gaze_video_frames.csv has the videos' frames")

        # Bad input: exit 2, a message naming it, no output.
        r = run(a.foveal, ["bench"] + SWEEP[:2] + ["--sigmas", "3", "--size", "64x36", "--frames", "1", "--shard", "2/4",
                                                   "--out", d("other-2")])
        check(r.returncode == 0, "a shard of another sweep runs")
        bad = [
            ([d("shard-1"), d("shard-2"), d("shard-3")], "shard 4/4 missing"),
            ([d("shard-1"), d("shard-2"), d("shard-2"), d("shard-3"), d("shard-4")], "shard 2/4 is given twice"),
            ([d("shard-1"), d("other-2"), d("shard-3"), d("shard-4")], "not the same sweep"),
            ([d("shard-1"), d("single")], "single/shard.json: missing"),
            ([d("nowhere")], "nowhere: no such directory"),
        ]
        with open(d("broken.json"), "w") as f:
            f.write("{")
        os.makedirs(d("broken"))
        shutil.copy(d("broken.json"), d("broken", "shard.json"))
        bad.append(([d("broken")], "broken/shard.json: not valid JSON"))
        for i, (shards, message) in enumerate(bad):
            r = run(a.foveal, ["bench", "merge", "--no-png", "--out", d(f"bad-{i}")] + shards)
            check(r.returncode == 2 and message in r.stderr and not os.path.exists(d(f"bad-{i}")),
                  f"merge exits 2 with '{message}' and writes nothing (got {r.returncode}: {r.stderr.strip()})")
        for spec in ("5/4", "0/4", "x", "2/", "1/0"):
            r = run(a.foveal, ["bench", "--scene", "pattern:noise", "--shard", spec, "--out", d("bad-shard")])
            check(r.returncode == 2 and "--shard" in r.stderr and not os.path.exists(d("bad-shard")),
                  f"--shard {spec}: exit 2 naming --shard, no output ({r.returncode}: {r.stderr.strip()})")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
