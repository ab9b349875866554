#!/usr/bin/env python3
"""Replace one method's rows of a committed bench run with a re-run's rows.

splice_method.py METHOD OLD_DIR NEW_DIR: in OLD_DIR's bench.csv, bench.json (rows),
rotation.csv, stability.csv and flicker.csv (those present in both), every row of
METHOD is replaced by NEW_DIR's rows of METHOD, in the old file's order (a row is matched
by its key columns); a key missing from the re-run is an error. Files are rewritten
atomically."""
import csv, io, json, os, sys

import chart_files

KEYS = {"bench.csv": ("scene", "method", "sigma"), "rotation.csv": ("angle_deg", "method", "sigma"),
        "stability.csv": ("scene", "path", "t", "method", "sigma"), "flicker.csv": ("scene", "pipeline", "camera", "method", "sigma", "gaze", "reference")}


def write_atomically(path, text):
    chart_files.write_text(path, text)


def key(row, cols):
    # flicker.csv from before the moving camera has no pipeline or camera column, and
    # from before --flicker-reference no reference column.
    defaults = {"pipeline": "gbuffer", "camera": "static", "reference": "gbuffer"}
    return tuple(str(float(row[c])) if c in ("sigma", "t") else str(row.get(c, defaults.get(c))) for c in cols)


def splice_csv(name, method, old_dir, new_dir):
    with open(os.path.join(old_dir, name), newline="") as f:
        old = list(csv.DictReader(f))
        fields = list(old[0].keys())
    with open(os.path.join(new_dir, name), newline="") as f:
        reader = csv.DictReader(f)
        new = {key(r, KEYS[name]): r for r in reader if r["method"] == method}
        # A re-run with other columns (JOD, say, or --no-jod) would leave a column half filled.
        if set(reader.fieldnames or []) != set(fields):
            sys.exit(f"{name}: the re-run's columns differ from the run's ({', '.join(sorted(set(reader.fieldnames or []) ^ set(fields)))}): "
                     "re-run with the same options (--no-jod where the run has no JOD columns)")
    out, used = [], 0
    for r in old:
        if r["method"] != method:
            out.append(r)
            continue
        k = key(r, KEYS[name])
        if k not in new:
            sys.exit(f"{name}: the re-run has no row {k}")
        out.append(new[k])
        used += 1
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    w.writerows(out)
    write_atomically(os.path.join(old_dir, name), buf.getvalue())
    print(f"{name}: {used} {method} rows replaced")


def splice_json(method, old_dir, new_dir):
    with open(os.path.join(old_dir, "bench.json")) as f:
        old = json.load(f)
    with open(os.path.join(new_dir, "bench.json")) as f:
        new = {(r["scene"], r["method"], float(r["sigma"])): r for r in json.load(f)["rows"] if r["method"] == method}
    used = 0
    for i, r in enumerate(old["rows"]):
        if r["method"] != method:
            continue
        k = (r["scene"], r["method"], float(r["sigma"]))
        if k not in new:
            sys.exit(f"bench.json: the re-run has no row {k}")
        old["rows"][i] = new[k]
        used += 1
    write_atomically(os.path.join(old_dir, "bench.json"), json.dumps(old, indent=2, ensure_ascii=False) + "\n")
    print(f"bench.json: {used} {method} rows replaced")


def main():
    method, old_dir, new_dir = sys.argv[1:4]
    for name in KEYS:
        if os.path.exists(os.path.join(old_dir, name)) and os.path.exists(os.path.join(new_dir, name)):
            splice_csv(name, method, old_dir, new_dir)
    if os.path.exists(os.path.join(old_dir, "bench.json")) and os.path.exists(os.path.join(new_dir, "bench.json")):
        splice_json(method, old_dir, new_dir)


if __name__ == "__main__":
    chart_files.run(main)
