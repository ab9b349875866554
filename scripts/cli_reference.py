#!/usr/bin/env python3
"""Writes docs/cli.md from the programs' own --help, or checks it against them.

    scripts/cli_reference.py            # regenerate docs/cli.md from build/bin
    scripts/cli_reference.py --check    # exit 1 naming the first command whose help differs

Programs: foveald and foveal (installed), and the OpenXR examples an app developer runs
(openxr_gaze, openxr_quad_views). foveal's subcommands, and theirs, are found in each
parent's "Subcommands:" list, so a new subcommand appears without editing this file.
--check also checks that every relative link and every docs/NAME.md named in README.md,
docs/cli.md and the pages they lead to first names a file that exists, and that none
points outside a clone (../shared).
Python 3 standard library only; programs run from argument lists, never through a shell.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PROGRAMS = ["foveald", "foveal", "openxr_gaze", "openxr_quad_views"]
# Nested subcommands deeper than this are not looked for (foveal has two levels).
MAX_DEPTH = 3
REGENERATE = "scripts/cli_reference.py"
# The front door and the pages it sends a new user to first.
LINKED_FILES = ["README.md", "docs/cli.md", "docs/commands.md", "docs/overview.md",
                "docs/layout.md", "docs/benchmarks.md"]

INTRO = """# Command-line reference

Generated from the programs' own `--help` by `{regen}` (after building:
`ninja -C build foveal foveald openxr_gaze openxr_quad_views`); the ctest test
`CliReference` runs `{regen} --check` and fails naming the first command whose help
differs from this file. Do not edit by hand: change the program's help, then regenerate.
What each command is for, with the figures behind it: [commands.md](commands.md).

- Every command and subcommand has `--help`; those that report have `--json`.
- Exit codes: 0 success, 2 bad input (the message names file, line and field), 1 internal
  error. Output files are written atomically: on failure nothing is left behind.
- Defaults shown under `$XDG_RUNTIME_DIR`, `$XDG_CONFIG_HOME` or `$HOME` are computed at
  run time from the user's directories; `$FOVEAL_DATA_DIR` stands for the folder that
  holds foveal's `data/`: the source tree for a build's programs, `<prefix>/share/foveal`
  when installed, or that variable when set.

Commands: {index}
"""

# Defaults that name the user's directories would differ per machine: the programs see
# these placeholders instead, so the file is the same wherever it is generated.
STABLE_ENV = {
    "HOME": "$HOME",
    "XDG_RUNTIME_DIR": "$XDG_RUNTIME_DIR",
    "XDG_CONFIG_HOME": "$XDG_CONFIG_HOME",
    "XDG_DATA_HOME": "$XDG_DATA_HOME",
    "FOVEAL_DATA_DIR": "$FOVEAL_DATA_DIR",
    "LC_ALL": "C.UTF-8",
}


class Failure(Exception):
    pass


def run_help(bin_dir, command, cwd):
    """The help text of command (a list: program, subcommands...), with argv[0] the
    program's bare name so the usage line does not depend on where the build is."""
    exe = bin_dir / command[0]
    if not exe.is_file():
        raise Failure(f"{exe}: not built (ninja -C build {command[0]})")
    env = {k: v for k, v in os.environ.items() if k not in STABLE_ENV}
    env.update(STABLE_ENV)
    try:
        res = subprocess.run(command + ["--help"], executable=str(exe), cwd=cwd, env=env,
                             stdin=subprocess.DEVNULL, capture_output=True, timeout=60)
    except subprocess.TimeoutExpired:
        raise Failure(f"`{' '.join(command)} --help` did not finish in 60 s")
    except OSError as e:
        raise Failure(f"{exe}: cannot run: {e.strerror} (being rebuilt?)")
    text = (res.stdout + res.stderr).decode("utf-8", errors="replace")
    if res.returncode != 0:
        raise Failure(f"`{' '.join(command)} --help` exited {res.returncode}:\n{text}")
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines())


def subcommands(help_text):
    """Names listed under CLI11's "Subcommands:" heading (two-space indent)."""
    names, inside = [], False
    for line in help_text.splitlines():
        if line.strip() == "Subcommands:":
            inside = True
        elif inside:
            m = re.match(r"^  ([A-Za-z0-9][\w-]*)(\s|$)", line)
            if m:
                names.append(m.group(1))
            elif line and not line.startswith("   "):
                inside = False
    return names


def collect(bin_dir, programs):
    """[(command words, help text)] for each program and, depth first, its subcommands."""
    out = []
    with tempfile.TemporaryDirectory(prefix="cli_reference.") as cwd:
        def walk(command):
            text = run_help(bin_dir, command, cwd)
            out.append((command, text))
            if len(command) < MAX_DEPTH:
                for sub in subcommands(text):
                    walk(command + [sub])
        for program in programs:
            walk([program])
    return out


def section(command, text):
    # The help never holds a line of three backticks, so a fence cannot end early.
    return f"## `{' '.join(command)}`\n\n```text\n{text}\n```\n"


def render(helps):
    index = ", ".join(f"`{' '.join(c)}`" for c, _ in helps if len(c) <= 2)
    head = INTRO.format(regen=REGENERATE, index=index)
    return head + "\n" + "\n".join(section(c, t) for c, t in helps)


def split_sections(doc):
    """{'foveal bench merge': section text} of a file render() wrote."""
    parts = re.split(r"(?m)^(?=## `)", doc)
    found = {}
    for part in parts[1:]:
        m = re.match(r"## `([^`]+)`", part)
        found[m.group(1)] = part.rstrip("\n") + "\n"
    return found


def first_difference(expected, actual):
    e, a = expected.splitlines(), actual.splitlines()
    for i in range(max(len(e), len(a))):
        el = e[i] if i < len(e) else "<end>"
        al = a[i] if i < len(a) else "<end>"
        if el != al:
            return f"    program: {el}\n    file:    {al}"
    return ""


def check(doc_path, helps, full):
    if not doc_path.is_file():
        raise Failure(f"{doc_path}: missing; write it with {REGENERATE}")
    doc = doc_path.read_text(encoding="utf-8")
    have = split_sections(doc)
    for command, text in helps:
        name = " ".join(command)
        want = section(command, text)
        if name not in have:
            raise Failure(f"{doc_path}: no section for `{name}` (a new command?); regenerate: {REGENERATE}")
        if have[name] != want.rstrip("\n") + "\n":
            raise Failure(f"{doc_path}: `{name} --help` differs from the program:\n"
                          f"{first_difference(want, have[name])}\nregenerate: {REGENERATE}")
    if full:
        names = {" ".join(c) for c, _ in helps}
        extra = [n for n in have if n not in names]
        if extra:
            raise Failure(f"{doc_path}: section `{extra[0]}` names no command the programs have; "
                          f"regenerate: {REGENERATE}")
        if doc != render(helps):
            raise Failure(f"{doc_path}: the introduction or the order differs; regenerate: {REGENERATE}")


LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
DOC_NAME = re.compile(r"(?<![\w/.])docs/[\w./-]*\.md")


def check_links(paths):
    """Every relative markdown link names an existing file inside the clone."""
    for rel in paths:
        path = ROOT / rel
        if not path.is_file():
            raise Failure(f"{rel}: missing")
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if "../shared" in line:
                raise Failure(f"{rel}:{n}: points outside a clone (../shared): {line.strip()}")
            for doc in DOC_NAME.findall(line):  # plain mentions are from the repository's root
                if not (ROOT / doc).is_file():
                    raise Failure(f"{rel}:{n}: names {doc}: no such file")
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                    continue  # http:, mailto:, an anchor in the same file
                file_part = target.split("#", 1)[0]
                resolved = (path.parent / file_part).resolve()
                if not resolved.exists():
                    raise Failure(f"{rel}:{n}: link to {target}: no such file")
                if ROOT not in resolved.parents and resolved != ROOT:
                    raise Failure(f"{rel}:{n}: link to {target} leaves the clone")


def write_atomic(path, text):
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    ap.add_argument("--bin-dir", type=Path, default=ROOT / "build" / "bin", help="where the programs are")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "cli.md", help="the reference file")
    ap.add_argument("--programs", nargs="+", default=PROGRAMS, metavar="PROGRAM",
                    help="check only these programs' sections (a build without OpenXR has no examples)")
    args = ap.parse_args()
    try:
        full = args.programs == PROGRAMS
        if not args.check and not full:
            raise Failure("--programs is for --check: the file always covers " + ", ".join(PROGRAMS))
        helps = collect(args.bin_dir, args.programs)
        if args.check:
            check(args.out, helps, full)
            check_links(LINKED_FILES)
            print(f"{args.out}: matches the --help of {len(helps)} commands; the links of "
                  f"{len(LINKED_FILES)} pages resolve")
        else:
            write_atomic(args.out, render(helps))
            print(f"{args.out}: {len(helps)} commands")
    except Failure as e:
        print(f"cli_reference: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
