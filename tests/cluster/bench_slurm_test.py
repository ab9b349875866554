#!/usr/bin/env python3
"""A bench sweep on a one-node Slurm cluster started here (slurm_cluster.py: munged,
slurmctld, slurmd on localhost, every file in a temporary directory, stopped at the
end): tools/cluster/submit_bench.sh submits it as a 4-task job array
(bench_array.sbatch, one `foveal bench --shard K/4` each) and a merge job that waits for
them; the merged bench.csv/json and every other table must equal a single-process run
of the same sweep row for row, timing columns left out (bench_rows.py).

Usage: bench_slurm_test.py --foveal BIN --source-dir DIR. Exit 0 passed, 1 failed (also
when slurm-wlm or munge is missing: the message says what to install).
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import bench_rows  # noqa: E402
from slurm_cluster import ClusterError, OneNodeCluster  # noqa: E402

N = 4


def sweep(source_dir):
    # A small grid over every method (the default list), a pattern and a real glTF, two
    # levels and a 2×2 f grid, at a tiny size: well under a minute of CPU in all.
    return ["--scene", "pattern:noise", "--scene", os.path.join(source_dir, "data/scenes/WaterBottle/WaterBottle.gltf"),
            "--sigmas", "2,2.6", "--size", "96x54", "--frames", "1", "--warmup", "0",
            "--f-grid", "--grid-values", "0.2,0.3"]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--foveal", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--keep", action="store_true", help="keep the cluster's and the sweep's files")
    a = p.parse_args()
    work = tempfile.mkdtemp(prefix="foveal-slurm-test-")
    failures = []

    def check(ok, what):
        print(("ok    " if ok else "FAIL  ") + what, flush=True)
        if not ok:
            failures.append(what)

    try:
        single = os.path.join(work, "single")
        r = subprocess.run([a.foveal, "bench"] + sweep(a.source_dir) + ["--no-png", "--out", single],
                           capture_output=True, text=True, timeout=300)
        check(r.returncode == 0, "the single-process run " + r.stderr.strip())
        out = os.path.join(work, "sweep")
        try:
            with OneNodeCluster(keep=a.keep) as cluster:
                print(f"cluster up: {cluster.dir}", flush=True)
                submit = os.path.join(a.source_dir, "tools/cluster/submit_bench.sh")
                env = cluster.env()
                env["FOVEAL"] = a.foveal
                r = subprocess.run([submit, "--wait", str(N), out] + sweep(a.source_dir), env=env,
                                   capture_output=True, text=True, timeout=600)
                print(r.stdout.strip(), flush=True)
                check(r.returncode == 0, f"submit_bench.sh --wait {N}: exit {r.returncode} {r.stderr.strip()}")
                if r.returncode != 0:
                    for log in sorted(glob.glob(os.path.join(out, "logs", "*"))):
                        print(f"--- {log}\n" + open(log, errors="replace").read())
                    print(cluster.logs())
        except ClusterError as e:
            check(False, f"the one-node Slurm cluster: {e}")
        if not failures:
            for k in range(1, N + 1):
                f = os.path.join(out, f"shard-{k}", "shard.json")
                shard = json.load(open(f))["rows"]["shard"] if os.path.exists(f) else None
                check(shard == [k, N], f"array task {k - 1} wrote shard {k}/{N} ({f})")
            check(os.path.exists(os.path.join(out, "logs", "merge.out")), "the merge ran as a Slurm job")
            diffs = bench_rows.differences(single, out)
            rows = len(bench_rows.table(os.path.join(single, "bench.csv"))) - 1
            check(not diffs and rows > 0,
                  f"the merged sweep equals the single run row for row ({rows} bench rows, f grid, auto f; timing "
                  f"left out: {', '.join(bench_rows.timing_columns(os.path.join(single, 'bench.csv')))}, cost_ratio)" +
                  "".join("\n      " + x for x in diffs[:10]))
            check(os.path.exists(os.path.join(out, "pareto.png")) and os.path.exists(os.path.join(out, "table.md")),
                  "the merge drew the charts")
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
